// A fixture for scripts.include_rule_catches_a_violation: retrieval/ must not reach into map/.
#pragma once
#include "map/surface_map.h"
