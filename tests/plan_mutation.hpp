// Helpers of the tests that break a shared plan on purpose: read it, edit one line, extract it
// through the real binary and look for the warning that names what was lost.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace bimloc::test {

std::string slurp(const std::string& path);
// Writes `contents` to DIR/NAME and returns that path.
std::string writeFile(const std::string& dir, const std::string& name, const std::string& contents);
// The text with `from` replaced by `to`; `from` must occur exactly once (a failed expectation
// otherwise: the plan changed under the test).
std::string mutated(const std::string& text, const std::string& from, const std::string& to);
// The id of the first instance of an IFC class in the text ("#390").
std::string firstOf(const std::string& text, const std::string& ifc_class);
// `bimloc extract PATH --out DIR --json` must fail: a non-zero exit, one line on stderr naming
// the file and holding `problem`, nothing on stdout, no output and no staging leftovers.
void expectCleanFailure(const std::string& path, const std::string& problem);
// `bimloc extract PATH --json`, expected to succeed; its JSON.
nlohmann::json extractJson(const std::string& path);
// Whether one warning of an extraction holds both strings.
bool anyWarningHas(const nlohmann::json& doc, const std::string& a, const std::string& b);

}  // namespace bimloc::test
