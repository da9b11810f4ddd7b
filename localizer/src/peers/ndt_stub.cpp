// Placeholder until NDT lands: never converges, says so.
#include "peers/peer.hpp"

namespace bimloc::peers {
namespace {
class NdtStub : public PeerLocalizer {
 public:
  bool wantsPoints(const Eigen::Isometry3d&) const override { return false; }
  PeerStep step(double, const Eigen::Isometry3d&, const std::vector<Eigen::Vector3f>*) override {
    PeerStep s;
    s.report.method = "ndt";
    s.warnings.push_back("ndt: not implemented yet");
    return s;
  }
};
}  // namespace
std::unique_ptr<PeerLocalizer> makeNdt(const bim::Storey&, const Eigen::Isometry3d&, const NdtConfig&, std::uint64_t) {
  return std::make_unique<NdtStub>();
}
}  // namespace bimloc::peers
