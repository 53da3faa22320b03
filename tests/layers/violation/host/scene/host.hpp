// The host may include anything below it.
#pragma once
#include "systems/lod/resolver.hpp"
