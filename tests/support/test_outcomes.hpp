#pragma once
// Every test that ran in this program, as the grader reads it: a JSON array of
// {"name", "status" (passed, failed or skipped), "failures" (the first few messages)}.
#include <nlohmann/json.hpp>

namespace springlab::testing {
nlohmann::json testOutcomes();
}
