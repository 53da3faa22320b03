// Umbrella header for the ECS core.
#pragma once

#include "engine/ecs/command_buffer.hpp"
#include "engine/ecs/entity.hpp"
#include "engine/ecs/group.hpp"
#include "engine/ecs/query.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/ecs/storage.hpp"
#include "engine/ecs/type_id.hpp"
#include "engine/ecs/view.hpp"
