// Planted violation for the layer check: a system including the host.
#pragma once
#include "engine/scene/world.hpp"
