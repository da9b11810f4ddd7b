// building.json: the extracted model as a versioned JSON document (schema in localizer/README.md).
#pragma once

#include <bimloc/bim/building.hpp>

#include <nlohmann/json.hpp>

namespace bimloc::bim {

// 2: "stairs" (issue 31). Version 1 documents still read, with no stairs.
constexpr int kBuildingJsonVersion = 2;

nlohmann::json toJson(const Building& building);
// Throws std::runtime_error naming the field on a document that is not a bimloc building.
Building buildingFromJson(const nlohmann::json& doc);

// The one-object summary of `bimloc extract --json`.
nlohmann::json extractionSummary(const Building& building, double seconds);

}  // namespace bimloc::bim
