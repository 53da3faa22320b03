// Planted violation for the layer check: a foundation including a system.
#pragma once
#include "engine/core/result.hpp"
#include "systems/lod/resolver.hpp"
