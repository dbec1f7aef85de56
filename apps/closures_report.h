#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/closure_metrics.h"

// The files `semchain bench closures` writes besides its picture: one CSV row a candidate, and
// the precision/recall tables as JSON and Markdown.
namespace semchain::app {

// One row a candidate: its nodes (graph index, scan index, timestamp from 'scan_times'),
// submap, score, relative pose, the stages it passed and its label.
std::string ClosuresCsv(const std::vector<eval::LabelledCandidate>& candidates,
                        const std::vector<double>& scan_times);

// The table: counts, and a row a threshold with each stage's accepted / true / false /
// unlabelled counts, precision and recall (null where undefined).
nlohmann::json ClosureTableJson(const eval::ClosureTable& table);

// How many true, false and unlabelled candidates scored within each 'step'-wide bin from
// 'lowest', and how many of each verification let through: where the score separates them.
nlohmann::json ScoreHistogramJson(const std::vector<eval::LabelledCandidate>& candidates,
                                  double lowest, double step);

// results.md from the results.json object `bench closures` writes.
std::string ClosuresMarkdown(const nlohmann::json& results);

}  // namespace semchain::app
