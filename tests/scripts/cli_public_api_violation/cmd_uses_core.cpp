// A product command that calls the core directly (scripts.cli_public_api_catches_a_violation).
#include "macrocon/macrocon.hpp"
#include "patch/geodesic_disk_patch.h"
