#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eval/closure_reference.h"
#include "mapping/loop_closure.h"

// The loop closer measured as a detector (`semchain bench closures`): each candidate it scored
// labelled by the reference, then precision and recall at each score threshold at three stages:
// the matcher's score alone, after verification (the gate and the confirmation rules: added to
// the graph) and after the back end (still in the graph at the end with at least half weight).
namespace semchain::eval {

enum class ClosureLabel { kTrue, kFalse, kUnlabelled };

struct ClosureLabelOptions {
  // A candidate is true when its relative pose is within these of the reference's.
  double max_translation_meters = 0.3;
  double max_rotation_radians = 0.034906585039886591;  // 2°
};

struct LabelledCandidate {
  mapping::LoopClosureCandidate candidate;
  ClosureLabel label = ClosureLabel::kUnlabelled;
  // How far the candidate's relative pose is from the reference's (labelled ones only).
  double translation_error_m = 0.0;
  double rotation_error_rad = 0.0;
};

// Labels 'candidate' (its from_scan and to_scan set) by 'reference'.
LabelledCandidate LabelCandidate(const mapping::LoopClosureCandidate& candidate,
                                 const ClosureReference& reference,
                                 const ClosureLabelOptions& options = {});

// The candidates one stage lets through at one threshold, by label.
struct StageCounts {
  int accepted = 0;
  int true_accepted = 0;
  int false_accepted = 0;
  int unlabelled_accepted = 0;
  std::optional<double> precision;  // true / (true + false); none when neither
  std::optional<double> recall;     // true accepted / true candidates; none when no true one
  // The same by search: of the nodes searched from that scored a true candidate (any submap),
  // the share with a true candidate accepted. A search adds one closure at most, and a place
  // seen from several submaps gives several true candidates: this is how many of the places
  // where a true closure was there to be found got one.
  int true_searches_accepted = 0;
  std::optional<double> search_recall;
};

struct ThresholdRow {
  double threshold = 0.0;
  StageCounts scored;    // score ≥ threshold
  StageCounts verified;  // ... and added to the graph (at once or confirmed)
  StageCounts back_end;  // ... and in the graph at the end with weight ≥ min_weight
};

struct ClosureTable {
  int candidates = 0;
  int true_candidates = 0;
  int false_candidates = 0;
  int unlabelled = 0;
  int true_searches = 0;  // nodes searched from with a true candidate
  std::vector<ThresholdRow> rows;
};

// Precision and recall of 'candidates' at each of 'thresholds'; a closure survives the back end
// with at least 'min_weight'.
ClosureTable PrecisionRecall(const std::vector<LabelledCandidate>& candidates,
                             const std::vector<double>& thresholds, double min_weight = 0.5);

const char* ToString(ClosureLabel label);
const char* ToString(mapping::ClosureVerification verification);

}  // namespace semchain::eval
