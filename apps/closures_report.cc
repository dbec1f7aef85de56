#include "apps/closures_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/angles.h"

namespace semchain::app {
// Helpers in a namespace of their own: unity builds compile several files as one.
namespace {
namespace closures_report {

std::string Fixed(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}

nlohmann::json StageJson(const eval::StageCounts& counts) {
  nlohmann::json json = {{"accepted", counts.accepted},
                         {"true", counts.true_accepted},
                         {"false", counts.false_accepted},
                         {"unlabelled", counts.unlabelled_accepted},
                         {"precision", nullptr},
                         {"recall", nullptr},
                         {"true_searches", counts.true_searches_accepted},
                         {"search_recall", nullptr}};
  if (counts.precision) json["precision"] = *counts.precision;
  if (counts.recall) json["recall"] = *counts.recall;
  if (counts.search_recall) json["search_recall"] = *counts.search_recall;
  return json;
}

// "n (true / false) | precision | recall | recall by search" of a stage's JSON.
std::string StageCell(const nlohmann::json& stage) {
  const auto ratio = [](const nlohmann::json& value) {
    return value.is_null() ? std::string("–") : Fixed(value.get<double>(), 2);
  };
  return std::to_string(stage["accepted"].get<int>()) + " (" +
         std::to_string(stage["true"].get<int>()) + " / " +
         std::to_string(stage["false"].get<int>()) + ") | " + ratio(stage["precision"]) + " | " +
         ratio(stage["recall"]) + " | " + ratio(stage["search_recall"]);
}

bool Verified(mapping::ClosureVerification v) {
  return v == mapping::ClosureVerification::kAdded || v == mapping::ClosureVerification::kConfirmed;
}

}  // namespace closures_report
}  // namespace

std::string ClosuresCsv(const std::vector<eval::LabelledCandidate>& candidates,
                        const std::vector<double>& scan_times) {
  std::ostringstream csv;
  csv << "from_node,to_node,from_scan,to_scan,from_time,to_time,submap,score,x,y,theta,"
         "best_of_search,passed_score,verification,innovation_sigmas,in_graph,residual_sigmas,"
         "weight,label,translation_error_m,rotation_error_deg\n";
  const auto time_of = [&scan_times](int scan) {
    return scan >= 0 && static_cast<std::size_t>(scan) < scan_times.size()
               ? closures_report::Fixed(scan_times[static_cast<std::size_t>(scan)], 6)
               : std::string();
  };
  for (const eval::LabelledCandidate& l : candidates) {
    const mapping::LoopClosureCandidate& c = l.candidate;
    const bool labelled = l.label != eval::ClosureLabel::kUnlabelled;
    csv << c.from << ',' << c.to << ',' << c.from_scan << ',' << c.to_scan << ','
        << time_of(c.from_scan) << ',' << time_of(c.to_scan) << ',' << c.submap << ','
        << closures_report::Fixed(c.score, 4) << ',' << closures_report::Fixed(c.relative.x, 4)
        << ',' << closures_report::Fixed(c.relative.y, 4) << ','
        << closures_report::Fixed(c.relative.theta, 5) << ',' << c.best_of_search << ','
        << c.passed_score << ',' << eval::ToString(c.verification) << ','
        << closures_report::Fixed(c.innovation_sigmas, 2) << ',' << c.in_graph << ','
        << closures_report::Fixed(c.residual_sigmas, 3) << ','
        << closures_report::Fixed(c.weight, 4) << ',' << eval::ToString(l.label) << ','
        << (labelled ? closures_report::Fixed(l.translation_error_m, 4) : std::string()) << ','
        << (labelled ? closures_report::Fixed(RadToDeg(l.rotation_error_rad), 3) : std::string())
        << '\n';
  }
  return csv.str();
}

nlohmann::json ClosureTableJson(const eval::ClosureTable& table) {
  nlohmann::json rows = nlohmann::json::array();
  for (const eval::ThresholdRow& row : table.rows) {
    rows.push_back({{"threshold", row.threshold},
                    {"scored", closures_report::StageJson(row.scored)},
                    {"verified", closures_report::StageJson(row.verified)},
                    {"back_end", closures_report::StageJson(row.back_end)}});
  }
  return {{"candidates", table.candidates},       {"true", table.true_candidates},
          {"false", table.false_candidates},      {"unlabelled", table.unlabelled},
          {"true_searches", table.true_searches}, {"rows", rows}};
}

nlohmann::json ScoreHistogramJson(const std::vector<eval::LabelledCandidate>& candidates,
                                  double lowest, double step) {
  nlohmann::json bins = nlohmann::json::array();
  for (double low = lowest; low < 1.0 - 1e-9; low += step) {
    const double high = low + step;
    int counts[3] = {0, 0, 0}, verified[3] = {0, 0, 0};
    for (const eval::LabelledCandidate& l : candidates) {
      const double score = l.candidate.score;
      if (score < low || (score >= high && high < 1.0 - 1e-9)) continue;
      const auto label = static_cast<std::size_t>(l.label);
      ++counts[label];
      if (closures_report::Verified(l.candidate.verification)) ++verified[label];
    }
    bins.push_back({{"from", low},
                    {"to", high},
                    {"true", counts[0]},
                    {"false", counts[1]},
                    {"unlabelled", counts[2]},
                    {"verified_true", verified[0]},
                    {"verified_false", verified[1]},
                    {"verified_unlabelled", verified[2]}});
  }
  return bins;
}

std::string ClosuresMarkdown(const nlohmann::json& r) {
  std::ostringstream md;
  const nlohmann::json& table = r["table"];
  md << "# semchain bench closures\n\n"
     << "log: `" << r["log"].get<std::string>()
     << "`; reference: " << r["reference"].get<std::string>()
     << "; config: " << r["config"].get<std::string>() << "; " << r["particles"]
     << " particles, seed " << r["seed"] << "; " << closures_report::Fixed(r["slam_seconds"], 1)
     << " s\n\n";
  if (r.value("oracle_verification", false)) {
    md << "**Oracle verification** (`--oracle`): the reference, not the loop closer, decided which "
          "closures went into the graph.\n\n";
  }
  md << "A candidate is the best match of one submap searched from one node (score ≥ "
     << closures_report::Fixed(r["record_min_score"], 2)
     << "), labelled true when its relative pose is within "
     << closures_report::Fixed(r["label_max_translation_m"], 2) << " m and "
     << closures_report::Fixed(r["label_max_rotation_deg"], 1)
     << "° of the reference's. Candidates: " << table["candidates"] << " (true " << table["true"]
     << ", false " << table["false"] << ", unlabelled " << table["unlabelled"]
     << "). Recall = true candidates accepted / true candidates scored; precision over the "
        "labelled ones. Stages: the score alone; after verification (added to the graph, at "
        "once or confirmed); after the back end (still in the graph at the end with weight ≥ "
     << closures_report::Fixed(r["min_weight"], 2) << "; loop loss "
     << r["loop_loss"].get<std::string>()
     << "). Cells: accepted (true / false) | precision | recall | Rs, recall by search: of the "
     << table["true_searches"]
     << " nodes searched from that scored a true candidate, the share with a true one accepted "
        "(a search adds one closure at most, and a place seen from several submaps gives "
        "several true candidates).\n\n";
  if (r.contains("accuracy")) {
    md << "Accuracy: " << r["accuracy_text"].get<std::string>() << "\n\n";
  }
  md << "| score ≥ | scored | P | R | Rs | verified | P | R | Rs | back end | P | R | Rs |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const nlohmann::json& row : table["rows"]) {
    md << "| " << closures_report::Fixed(row["threshold"], 2) << " | "
       << closures_report::StageCell(row["scored"]) << " | "
       << closures_report::StageCell(row["verified"]) << " | "
       << closures_report::StageCell(row["back_end"]) << " |\n";
  }
  md << "\n## Scores of true and false candidates\n\n"
     << "| score | true | false | unlabelled | verified true | verified false |\n"
        "|---|---|---|---|---|---|\n";
  for (const nlohmann::json& bin : r["histogram"]) {
    md << "| " << closures_report::Fixed(bin["from"], 2) << "–"
       << closures_report::Fixed(bin["to"], 2) << " | " << bin["true"] << " | " << bin["false"]
       << " | " << bin["unlabelled"] << " | " << bin["verified_true"] << " | "
       << bin["verified_false"] << " |\n";
  }
  md << "\n## False candidates that reached the graph\n\n";
  if (r["false_in_graph"].empty()) md << "none\n";
  for (const nlohmann::json& c : r["false_in_graph"]) {
    md << "- nodes " << c["from_node"] << " → " << c["to_node"] << " (scans " << c["from_scan"]
       << " → " << c["to_scan"] << "), score " << closures_report::Fixed(c["score"], 3) << ", "
       << c["verification"].get<std::string>() << ", off by "
       << closures_report::Fixed(c["translation_error_m"], 2) << " m / "
       << closures_report::Fixed(c["rotation_error_deg"], 1) << "°, in the graph at the end: "
       << (c["in_graph"].get<bool>() ? "yes, weight " + closures_report::Fixed(c["weight"], 3)
                                     : std::string("no"))
       << "\n";
  }
  return md.str();
}

}  // namespace semchain::app
