#include "sim/cli/localize_output.hpp"

#include "sim/cli/snapshots.hpp"
#include "sim/dataset/bag_reader.hpp"
#include "sim/dataset/localized_bag_writer.hpp"
#include "sim/dataset/localized_mcap_writer.hpp"
#include "sim/dataset/tum_writer.hpp"
#include "sim/render/snapshot.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <cmath>
#include <filesystem>

namespace bimloc::cli {
namespace {

std::uint64_t nanoseconds(double s) { return static_cast<std::uint64_t>(std::llround(s * 1e9)); }

}  // namespace

LocalizeOutput::LocalizeOutput(const std::string& dir, const std::string& input_bag, const LocalizeOutputFrames& frames,
                               const bim::Building& building, const Localizer& localizer)
    : staging_(dir, {"report.json", "bimloc.localize"}), building_(building), localizer_(localizer) {
  trajectory_ = std::make_unique<sim::TumWriter>(
      staging_.file("trajectory.tum"),
      "timestamp tx ty tz qx qy qz qw: T_map_base, " + frames.base + " in " + frames.map +
          " (the plan's frame), at each lidar turn once localized");
  if (!input_bag.empty() && !sim::isRosBag(input_bag))
    mcap_ = std::make_unique<sim::LocalizedMcapWriter>(staging_.file("localized.mcap"), input_bag, frames.map, frames.odom,
                                                       frames.base, frames.tf_topic);
  else if (!input_bag.empty())
    bag_ = std::make_unique<sim::LocalizedBagWriter>(staging_.file("localized.bag"), input_bag, frames.map, frames.odom,
                                                     frames.base, frames.tf_topic);
  std::filesystem::create_directory(staging_.file("snapshots"));
}

LocalizeOutput::~LocalizeOutput() = default;

void LocalizeOutput::snapshot(const std::string& phase, double time_s, const LocalizationResult& r,
                              const std::optional<Eigen::Isometry3d>& truth) {
  sim::SnapshotScene scene;
  const std::size_t storey = r.storey ? *r.storey : r.leading_storey;
  scene.storey = &building_.storeys.at(storey);
  if (truth) scene.truth = planarPose(*truth);
  scene.estimate = planarPose(r.T_map_base);
  scene.title = "localize";
  scene.time_s = time_s;
  scene.phase = phase;
  if (const pf::StoreyBank* bank = localizer_.filter(); bank && !localizer_.tracker()) {
    double max_lw = -1e300;
    const auto& particles = bank->filter().particles();
    for (const auto& p : particles) max_lw = std::max(max_lw, p.log_weight);
    for (const auto& p : particles) scene.particles.push_back({p.x, p.y, p.yaw, std::exp(p.log_weight - max_lw)});
  }
  scene.legend_extra.push_back({"state", toString(r.state)});
  scene.legend_extra.push_back({"storey", scene.storey->name});
  if (const auto* tracker = localizer_.tracker()) scene.graph = snapshotGraph(*tracker, *scene.storey);
  char file[64];
  std::snprintf(file, sizeof file, "snapshots/%d_%s.png", snapshots_++, phase.c_str());
  sim::renderSnapshot(scene, staging_.file(file));
}

void LocalizeOutput::step(const sim::RecordedTurn& turn, const LocalizationResult& r,
                          const std::optional<Eigen::Isometry3d>& truth) {
  if (!start_s_) start_s_ = turn.stamp_s;
  // Only once localized: before that the filter's best guess jumps between hypotheses, which
  // is no trajectory (and no map -> odom to publish).
  if (r.T_map_odom) {
    trajectory_->add(nanoseconds(turn.stamp_s), r.T_map_base);
    if (bag_) bag_->add(turn.stamp_s, *r.T_map_odom, r.T_map_base, r.covariance);
    if (mcap_) mcap_->add(turn.stamp_s, *r.T_map_odom, r.T_map_base, r.covariance);
  }
  if (r.state == LocalizationState::Converged && !converged_) {
    converged_ = true;
    snapshot("convergence", turn.stamp_s - *start_s_, r, truth);
  }
  last_ = r;
  last_truth_ = truth;
}

void LocalizeOutput::commit(const nlohmann::json& report, const sim::ScenarioResult& result) {
  if (last_) snapshot("end", last_->stamp_s - start_s_.value_or(last_->stamp_s), *last_, last_truth_);
  writeErrorPlot(staging_.path(), "snapshots", result);  // snapshots/errors.png
  trajectory_->close();
  if (bag_) bag_->close();
  if (mcap_) mcap_->close(building_.storeys.at(last_ ? (last_->storey ? *last_->storey : last_->leading_storey) : 0));
  nlohmann::json j = report;
  j["format"] = "bimloc.localize";
  sim::writeFileAtomically(staging_.file("report.json"), j.dump(2) + "\n");
  staging_.commit();
}

}  // namespace bimloc::cli
