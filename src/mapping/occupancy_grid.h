#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

// A log-odds occupancy grid that grows as it is written and is shared copy-on-write: the cells
// live in fixed-size square patches held by shared_ptr, a copy of the grid shares every patch,
// and a write clones only the patch it touches when another grid still holds it. N particles
// whose maps descend from one another therefore use memory for what differs, not N × map
// (DESIGN.md §3.2).
namespace semchain::mapping {

struct OccupancyGridOptions {
  double resolution_meters = 0.05;
  // Log-odds added per hit and per pass-through: log(0.7 / 0.3) and log(0.4 / 0.6).
  double hit_log_odds = 0.847;
  double miss_log_odds = -0.405;
  // Cells are clamped to this log-odds range so that a changed world can be relearnt.
  double max_abs_log_odds = 6.0;

  bool Validate(std::string* error) const;
};

// One cell. Besides the log-odds it keeps the running mean of the beam endpoints that fell in
// it, relative to the cell centre, so that scan matching has sub-cell accuracy.
struct GridCell {
  float log_odds = 0.0f;
  float mean_x = 0.0f;  // metres, relative to the cell centre
  float mean_y = 0.0f;
  std::uint16_t hits = 0;          // saturating
  std::uint16_t observations = 0;  // saturating; 0 = never observed (unknown)

  bool Known() const { return observations > 0; }
};

// The inclusive range of cell indices [min, max]; empty when min > max.
struct CellBox {
  Eigen::Vector2i min{0, 0};
  Eigen::Vector2i max{-1, -1};
  bool empty() const { return min.x() > max.x() || min.y() > max.y(); }
  int width() const { return empty() ? 0 : max.x() - min.x() + 1; }
  int height() const { return empty() ? 0 : max.y() - min.y() + 1; }
};

class OccupancyGrid {
 public:
  static constexpr int kPatchBits = 4;
  static constexpr int kPatchSize = 1 << kPatchBits;  // cells per patch side
  struct Patch {
    GridCell cells[kPatchSize * kPatchSize];
  };

  // Cell (i, j) covers [origin + (i, j) * resolution, origin + (i + 1, j + 1) * resolution).
  explicit OccupancyGrid(const OccupancyGridOptions& options = {},
                         const Eigen::Vector2d& origin = Eigen::Vector2d::Zero());

  // Copies are cheap: they share every patch until one side writes to it.
  OccupancyGrid(const OccupancyGrid&) = default;
  OccupancyGrid& operator=(const OccupancyGrid&) = default;
  OccupancyGrid(OccupancyGrid&&) = default;
  OccupancyGrid& operator=(OccupancyGrid&&) = default;

  const OccupancyGridOptions& options() const { return options_; }
  double resolution() const { return options_.resolution_meters; }
  const Eigen::Vector2d& origin() const { return origin_; }

  // The cell containing 'world' (floor, as map_server does).
  Eigen::Vector2i CellOf(const Eigen::Vector2d& world) const {
    return {static_cast<int>(std::floor((world.x() - origin_.x()) * inverse_resolution_)),
            static_cast<int>(std::floor((world.y() - origin_.y()) * inverse_resolution_))};
  }
  Eigen::Vector2d CellCenter(const Eigen::Vector2i& cell) const {
    return origin_ + (cell.cast<double>() + Eigen::Vector2d(0.5, 0.5)) * resolution();
  }

  // The cell, or nullptr where no patch was ever written (unknown).
  const GridCell* Find(const Eigen::Vector2i& cell) const {
    const int px = (cell.x() >> kPatchBits) - patch_min_.x();
    const int py = (cell.y() >> kPatchBits) - patch_min_.y();
    if (px < 0 || py < 0 || px >= patches_x_ || py >= patches_y_) return nullptr;
    const Patch* patch = patches_[static_cast<std::size_t>(py * patches_x_ + px)].get();
    if (patch == nullptr) return nullptr;
    return &patch->cells[((cell.y() & (kPatchSize - 1)) << kPatchBits) |
                         (cell.x() & (kPatchSize - 1))];
  }

  // Fills 'out' with the (2k+1)² cells around 'center', row by row from (-k, -k) (nullptr where
  // no patch exists); a fast path serves blocks that lie inside one patch.
  void FetchBlock(const Eigen::Vector2i& center, int k, const GridCell** out) const {
    const int lx = center.x() & (kPatchSize - 1);
    const int ly = center.y() & (kPatchSize - 1);
    if (lx >= k && ly >= k && lx < kPatchSize - k && ly < kPatchSize - k) {
      const int px = (center.x() >> kPatchBits) - patch_min_.x();
      const int py = (center.y() >> kPatchBits) - patch_min_.y();
      const Patch* patch = nullptr;
      if (px >= 0 && py >= 0 && px < patches_x_ && py < patches_y_) {
        patch = patches_[static_cast<std::size_t>(py * patches_x_ + px)].get();
      }
      for (int dy = -k, i = 0; dy <= k; ++dy) {
        for (int dx = -k; dx <= k; ++dx, ++i) {
          out[i] =
              patch == nullptr ? nullptr : &patch->cells[((ly + dy) << kPatchBits) | (lx + dx)];
        }
      }
      return;
    }
    for (int dy = -k, i = 0; dy <= k; ++dy) {
      for (int dx = -k; dx <= k; ++dx, ++i) out[i] = Find(center + Eigen::Vector2i(dx, dy));
    }
  }

  // Log-odds of a cell, 0 where unknown.
  float LogOdds(const Eigen::Vector2i& cell) const {
    const GridCell* c = Find(cell);
    return c == nullptr ? 0.0f : c->log_odds;
  }

  // Records a beam ending at 'world' inside 'cell' (= CellOf(world)).
  void AddHit(const Eigen::Vector2i& cell, const Eigen::Vector2d& world);
  // Records a beam passing through 'cell'.
  void AddMiss(const Eigen::Vector2i& cell);
  // Sets a cell outright (used when loading a map from an image).
  void SetCell(const Eigen::Vector2i& cell, const GridCell& value);

  // The smallest box holding every observed cell.
  CellBox KnownBounds() const;
  // Number of allocated patches and the ids of their storage (for memory accounting: patches
  // shared between grids have the same id).
  std::size_t PatchCount() const;
  void CollectPatchIds(std::vector<const void*>* ids) const;
  static constexpr std::size_t PatchBytes() { return sizeof(Patch); }

 private:
  // The cell for writing: grows the patch table, allocates or clones the patch as needed.
  GridCell& MutableCell(const Eigen::Vector2i& cell);
  void GrowToInclude(const Eigen::Vector2i& patch_index);

  OccupancyGridOptions options_;
  Eigen::Vector2d origin_;
  double inverse_resolution_;
  Eigen::Vector2i patch_min_{0, 0};  // patch index of patches_[0]
  int patches_x_ = 0;
  int patches_y_ = 0;
  std::vector<std::shared_ptr<Patch>> patches_;  // row-major, patches_x_ × patches_y_
};

// Log-odds to probability and back.
inline double LogOddsToProbability(double log_odds) { return 1.0 / (1.0 + std::exp(-log_odds)); }
inline double ProbabilityToLogOdds(double p) { return std::log(p / (1.0 - p)); }

// Bytes held by the distinct patches of 'grids' (a patch shared by several grids counts once).
std::size_t UniquePatchBytes(const std::vector<const OccupancyGrid*>& grids);

}  // namespace semchain::mapping
