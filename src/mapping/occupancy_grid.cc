#include "mapping/occupancy_grid.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <unordered_set>

#include "core/check.h"

namespace semchain::mapping {
namespace {

constexpr int kGrowthMarginPatches = 4;

void SaturatingIncrement(std::uint16_t& count) {
  if (count < std::numeric_limits<std::uint16_t>::max()) ++count;
}

}  // namespace

bool OccupancyGridOptions::Validate(std::string* error) const {
  if (!(resolution_meters > 0.0 && resolution_meters <= 10.0)) {
    *error = "resolution_meters must be in (0, 10]";
    return false;
  }
  if (!(hit_log_odds > 0.0)) {
    *error = "hit_log_odds must be positive";
    return false;
  }
  if (!(miss_log_odds < 0.0)) {
    *error = "miss_log_odds must be negative";
    return false;
  }
  if (!(max_abs_log_odds >= hit_log_odds && max_abs_log_odds >= -miss_log_odds)) {
    *error = "max_abs_log_odds must be at least |hit_log_odds| and |miss_log_odds|";
    return false;
  }
  return true;
}

OccupancyGrid::OccupancyGrid(const OccupancyGridOptions& options, const Eigen::Vector2d& origin)
    : options_(options), origin_(origin), inverse_resolution_(1.0 / options.resolution_meters) {
  std::string error;
  SEMCHAIN_CHECK(options_.Validate(&error));
}

void OccupancyGrid::GrowToInclude(const Eigen::Vector2i& patch_index) {
  if (patches_x_ > 0 && patch_index.x() >= patch_min_.x() && patch_index.y() >= patch_min_.y() &&
      patch_index.x() < patch_min_.x() + patches_x_ &&
      patch_index.y() < patch_min_.y() + patches_y_) {
    return;
  }
  Eigen::Vector2i new_min = patch_index.array() - kGrowthMarginPatches;
  Eigen::Vector2i new_max = patch_index.array() + kGrowthMarginPatches;
  if (patches_x_ > 0) {
    new_min = new_min.cwiseMin(patch_min_);
    new_max = new_max.cwiseMax(patch_min_ + Eigen::Vector2i(patches_x_ - 1, patches_y_ - 1));
  }
  const int new_x = new_max.x() - new_min.x() + 1;
  const int new_y = new_max.y() - new_min.y() + 1;
  std::vector<std::shared_ptr<Patch>> table(static_cast<std::size_t>(new_x) * new_y);
  for (int y = 0; y < patches_y_; ++y) {
    for (int x = 0; x < patches_x_; ++x) {
      const int nx = x + patch_min_.x() - new_min.x();
      const int ny = y + patch_min_.y() - new_min.y();
      table[static_cast<std::size_t>(ny * new_x + nx)] =
          std::move(patches_[static_cast<std::size_t>(y * patches_x_ + x)]);
    }
  }
  patches_ = std::move(table);
  patch_min_ = new_min;
  patches_x_ = new_x;
  patches_y_ = new_y;
}

GridCell& OccupancyGrid::MutableCell(const Eigen::Vector2i& cell) {
  const Eigen::Vector2i patch_index(cell.x() >> kPatchBits, cell.y() >> kPatchBits);
  GrowToInclude(patch_index);
  const Eigen::Vector2i local = patch_index - patch_min_;
  std::shared_ptr<Patch>& patch =
      patches_[static_cast<std::size_t>(local.y() * patches_x_ + local.x())];
  if (patch == nullptr) {
    patch = std::make_shared<Patch>();
  } else if (patch.use_count() > 1) {
    // Copy-on-write: another grid still reads this patch.
    patch = std::make_shared<Patch>(*patch);
  } else {
    // Sole owner. Pairs with the release in the other owner's reference drop, so that its
    // last reads of the patch happen before our writes.
    std::atomic_thread_fence(std::memory_order_acquire);
  }
  return patch
      ->cells[((cell.y() & (kPatchSize - 1)) << kPatchBits) | (cell.x() & (kPatchSize - 1))];
}

void OccupancyGrid::AddHit(const Eigen::Vector2i& cell, const Eigen::Vector2d& world) {
  GridCell& c = MutableCell(cell);
  const auto limit = static_cast<float>(options_.max_abs_log_odds);
  c.log_odds = std::min(limit, c.log_odds + static_cast<float>(options_.hit_log_odds));
  SaturatingIncrement(c.hits);
  SaturatingIncrement(c.observations);
  const Eigen::Vector2d offset = world - CellCenter(cell);
  const float gain = 1.0f / static_cast<float>(std::min<std::uint16_t>(c.hits, 1000));
  c.mean_x += gain * (static_cast<float>(offset.x()) - c.mean_x);
  c.mean_y += gain * (static_cast<float>(offset.y()) - c.mean_y);
}

void OccupancyGrid::AddMiss(const Eigen::Vector2i& cell) {
  GridCell& c = MutableCell(cell);
  const auto limit = static_cast<float>(options_.max_abs_log_odds);
  c.log_odds = std::max(-limit, c.log_odds + static_cast<float>(options_.miss_log_odds));
  SaturatingIncrement(c.observations);
}

void OccupancyGrid::SetCell(const Eigen::Vector2i& cell, const GridCell& value) {
  MutableCell(cell) = value;
}

CellBox OccupancyGrid::KnownBounds() const {
  CellBox box;
  box.min = Eigen::Vector2i::Constant(std::numeric_limits<int>::max());
  box.max = Eigen::Vector2i::Constant(std::numeric_limits<int>::min());
  for (int py = 0; py < patches_y_; ++py) {
    for (int px = 0; px < patches_x_; ++px) {
      const Patch* patch = patches_[static_cast<std::size_t>(py * patches_x_ + px)].get();
      if (patch == nullptr) continue;
      for (int i = 0; i < kPatchSize * kPatchSize; ++i) {
        if (!patch->cells[i].Known()) continue;
        const Eigen::Vector2i cell((px + patch_min_.x()) * kPatchSize + (i & (kPatchSize - 1)),
                                   (py + patch_min_.y()) * kPatchSize + (i >> kPatchBits));
        box.min = box.min.cwiseMin(cell);
        box.max = box.max.cwiseMax(cell);
      }
    }
  }
  if (box.min.x() == std::numeric_limits<int>::max()) return CellBox{};
  return box;
}

std::size_t OccupancyGrid::PatchCount() const {
  return static_cast<std::size_t>(
      std::count_if(patches_.begin(), patches_.end(), [](const auto& p) { return p != nullptr; }));
}

void OccupancyGrid::CollectPatchIds(std::vector<const void*>* ids) const {
  for (const auto& patch : patches_) {
    if (patch != nullptr) ids->push_back(patch.get());
  }
}

std::size_t UniquePatchBytes(const std::vector<const OccupancyGrid*>& grids) {
  std::vector<const void*> ids;
  for (const OccupancyGrid* grid : grids) grid->CollectPatchIds(&ids);
  const std::unordered_set<const void*> unique(ids.begin(), ids.end());
  return unique.size() * OccupancyGrid::PatchBytes();
}

}  // namespace semchain::mapping
