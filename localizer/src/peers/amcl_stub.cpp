// Placeholder until AMCL lands: never converges, says so.
#include "peers/peer.hpp"

namespace bimloc::peers {
namespace {
class AmclStub : public PeerLocalizer {
 public:
  bool wantsPoints(const Eigen::Isometry3d&) const override { return false; }
  PeerStep step(double, const Eigen::Isometry3d&, const std::vector<Eigen::Vector3f>*) override {
    PeerStep s;
    s.report.method = "amcl";
    s.warnings.push_back("amcl: not implemented yet");
    return s;
  }
};
}  // namespace
std::unique_ptr<PeerLocalizer> makeAmcl(const bim::Storey&, const Eigen::Isometry3d&, const AmclConfig&, std::uint64_t) {
  return std::make_unique<AmclStub>();
}
}  // namespace bimloc::peers
