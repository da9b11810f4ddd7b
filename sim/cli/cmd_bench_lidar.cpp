// bimloc bench lidar --plan PLAN [--storey S] [--threads N] [--turns K] [--json]
// The full VLP-16 model (noise, fields, distortion, packets) against a bare rtcIntersect1
// loop over exactly the same rays on the same scene, in the same run.
#include "sim/cli/commands.hpp"
#include "sim/cli/table.hpp"
#include "sim/lidar/vlp16.hpp"
#include "sim/world/world.hpp"

#include <embree3/rtcore.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <optional>
#include <chrono>
#include <iostream>
#include <thread>

namespace {

using namespace bimloc::sim;
using Clock = std::chrono::steady_clock;

struct LidarBenchArgs {
  std::string plan;
  std::string storey = "0";
  int threads = 1;
  int turns = 20;
  int rounds = 5;
  bool json = false;
  std::string site;  // also time the model on this site of the plan (sim/world/site_config.hpp)
};

// The base walks a slow circle around the largest room's centre while turning: every firing
// is cast from its own pose, as in a real scenario.
std::function<Eigen::Isometry3d(double)> benchBase(const World& world, std::size_t storey) {
  const auto& rooms = world.building().storeys[storey].rooms;
  Eigen::Vector3d centre(0, 0, world.building().storeys[storey].elevation_m);
  double best = -1;
  for (const auto& r : rooms)
    if (r.area_m2 > best) best = r.area_m2, centre = Eigen::Vector3d(r.centre.x(), r.centre.y(), r.floor_z);
  return [centre](double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = centre + Eigen::Vector3d(0.3 * std::cos(0.5 * t), 0.3 * std::sin(0.5 * t), 0.5);
    T.linear() = Eigen::AngleAxisd(0.5 * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
  };
}

// Runs `job(i)` for i in [0, n) on `threads` threads; returns the wall time in seconds.
double timed(int threads, int n, const std::function<void(int)>& job) {
  std::atomic<int> next{0};
  const auto work = [&] {
    for (int i = next++; i < n; i = next++) job(i);
  };
  const auto t0 = Clock::now();
  std::vector<std::thread> pool;
  for (int w = 1; w < threads; ++w) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void run(const LidarBenchArgs& args) {
  const World world = World::load(args.plan);
  const std::size_t storey = world.storeyIndex(args.storey);
  const auto base = benchBase(world, storey);
  Vlp16Config config;
  RayRecord rays;
  Vlp16(config).scan(world, storey, base, 0.0, 1, 0, &rays);
  const auto n_rays = static_cast<int>(rays.origins.size());
  auto scene = static_cast<RTCScene>(world.embreeScene(storey));

  // The reference: a bare rtcIntersect1 loop over the same rays, in firing order, K times.
  std::atomic<std::uint64_t> hits{0};
  const auto plain_time = [&] {
    hits = 0;
    return timed(args.threads, args.turns, [&](int) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      std::uint64_t h = 0;
      for (int r = 0; r < n_rays; ++r) {
        RTCRayHit rh{};
        rh.ray.org_x = rays.origins[r].x(), rh.ray.org_y = rays.origins[r].y(), rh.ray.org_z = rays.origins[r].z();
        rh.ray.dir_x = rays.directions[r].x(), rh.ray.dir_y = rays.directions[r].y(), rh.ray.dir_z = rays.directions[r].z();
        rh.ray.tnear = 0.05f, rh.ray.tfar = 101.0f, rh.ray.mask = 0xFFFFFFFFu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rh);
        h += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
      hits += h;
    });
  };
  // The model, with packets (the default) and with single rays.
  // The site's world (same plan, same poses): partitions, door leaves, glass filters.
  const std::optional<World> site =
      args.site.empty() ? std::nullopt : std::optional<World>(world.withSite(sitePreset(args.site), 1));
  const auto model_time = [&](bool packets, const World* on) {
    Vlp16Config c = config;
    c.use_packets = packets;
    const Vlp16 lidar(c);
    const World& w = on ? *on : world;
    return timed(args.threads, args.turns, [&](int i) {
      lidar.scan(w, storey, base, i * lidar.turnPeriod_s(), 1, static_cast<std::uint64_t>(i));
    });
  };
  // Interleaved rounds, best of each: the machine is shared, and whatever else runs slows
  // every variant of a round alike; the fastest round is the least disturbed one.
  double plain_s = 1e30, model_s = 1e30, single_s = 1e30, site_s = 1e30;
  for (int round = 0; round < args.rounds; ++round) {
    plain_s = std::min(plain_s, plain_time());
    model_s = std::min(model_s, model_time(true, nullptr));
    single_s = std::min(single_s, model_time(false, nullptr));
    if (site) site_s = std::min(site_s, model_time(true, &*site));
  }
  const double total_rays = double(n_rays) * args.turns;
  nlohmann::json result = {
      {"plan", args.plan}, {"storey", world.building().storeyLabel(storey)}, {"threads", args.threads},
      {"triangles", world.triangleCount(storey)}, {"rays", n_rays}, {"turns", args.turns}, {"rounds", args.rounds},
      {"plain_rays_per_s", total_rays / plain_s}, {"model_rays_per_s", total_rays / model_s},
      {"ratio", plain_s / model_s}, {"turns_per_s", args.turns / model_s},
      {"model_single_ray_rays_per_s", total_rays / single_s}, {"ratio_single_ray", plain_s / single_s},
      {"hit_fraction", double(hits) / total_rays}};
  if (site) {
    result["site"] = args.site;
    result["site_model_rays_per_s"] = total_rays / site_s;
    result["site_vs_exact"] = model_s / site_s;  // the issue asks for >= 0.8
  }
  if (args.json) {
    std::cout << result.dump() << "\n";
    return;
  }
  using bimloc::cli::fixed;
  bimloc::cli::Table table({"variant", "M rays/s", "vs plain", "turns/s"});
  table.add({"plain rtcIntersect1 loop", fixed(total_rays / plain_s / 1e6, 2), "1.00", fixed(args.turns / plain_s, 1)});
  table.add({"VLP-16 model, packets", fixed(total_rays / model_s / 1e6, 2), fixed(plain_s / model_s, 2),
             fixed(args.turns / model_s, 1)});
  table.add({"VLP-16 model, single rays", fixed(total_rays / single_s / 1e6, 2), fixed(plain_s / single_s, 2),
             fixed(args.turns / single_s, 1)});
  if (site)
    table.add({"VLP-16 model, packets, site " + args.site, fixed(total_rays / site_s / 1e6, 2), fixed(plain_s / site_s, 2),
               fixed(args.turns / site_s, 1)});
  std::cout << bimloc::cli::wrapText(args.plan + ", storey '" + world.building().storeyLabel(storey) + "': " +
                                         std::to_string(world.triangleCount(storey)) + " triangles, " + std::to_string(n_rays) +
                                         " rays a turn, " + std::to_string(args.turns) + " turns, " + std::to_string(args.threads) +
                                         " thread(s)",
                                     bimloc::cli::kTableColumns)
            << "\n";
  table.print(std::cout);
}

}  // namespace

void addBenchLidarCommand(CLI::App& bench) {
  auto args = std::make_shared<LidarBenchArgs>();
  CLI::App* cmd = bench.add_subcommand(
      "lidar", "The VLP-16 model (noise, fields, distortion, 16-ray packets) against a bare rtcIntersect1 loop\n"
               "over exactly the same rays on the same scene, measured in the same run.");
  cmd->add_option("--plan", args->plan, "IFC plan, extract folder or mesh")->required();
  cmd->add_option("--storey", args->storey, bimloc::cli::kStoreyHelp);
  cmd->add_option("--threads", args->threads, "threads for both loops")->check(CLI::Range(1, 256));
  cmd->add_option("--turns", args->turns, "turns per measurement")->check(CLI::Range(1, 100000));
  cmd->add_option("--rounds", args->rounds, "interleaved rounds; the best of each variant is reported")->check(CLI::Range(1, 100));
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->add_option("--site", args->site,
                  "also time the model on this site of the plan (as_built, construction, heavy; seed 1), interleaved "
                  "with the others: site_vs_exact is its speed over the plan's world's")
      ->check(bimloc::cli::siteCheck());
  cmd->callback([args] { run(*args); });
}
