// A fixture for scripts.include_rule_catches_a_violation (an allowed, empty header).
#pragma once
