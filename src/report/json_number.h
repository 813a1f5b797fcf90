#pragma once
// The one way gbufferlab writes a double into JSON (report.json, search.json, `diff --json`):
// JSON has no infinity or NaN, so a finite value is a number and a non-finite one a string:
// "inf", "-inf" or "nan" (docs/report-schema.md). null stays free to mean "not measured".
#include <cmath>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

namespace gbl {

template <class Json = nlohmann::ordered_json>
Json jsonNumber(double v) {
    if (std::isfinite(v)) return Json(v);
    if (std::isnan(v)) return Json("nan");
    return Json(v > 0 ? "inf" : "-inf");
}

// The reverse, for readers: a number, "inf", "-inf", "nan", or null (reports written before
// "nan" existed wrote NaN as null) -> the double; false for anything else.
template <class Json>
bool readJsonNumber(const Json& j, double& out) {
    if (j.is_number()) {
        out = j.template get<double>();
        return true;
    }
    if (j.is_null()) {
        out = std::numeric_limits<double>::quiet_NaN();
        return true;
    }
    if (!j.is_string()) return false;
    const std::string& s = j.template get_ref<const std::string&>();
    if (s == "inf") out = std::numeric_limits<double>::infinity();
    else if (s == "-inf") out = -std::numeric_limits<double>::infinity();
    else if (s == "nan") out = std::numeric_limits<double>::quiet_NaN();
    else return false;
    return true;
}

}  // namespace gbl
