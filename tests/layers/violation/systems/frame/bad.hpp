// Planted violation for the layer check: a system including the host.
#pragma once
#include "host/scene/world.hpp"
