// An HDL-style NDT localizer (hdl_localization + hdl_global_localization) as the paper's
// second baseline. Defaults from ../shared/reference.md, "Baselines".
#pragma once

namespace bimloc::peers {

struct NdtConfig {
  double ndt_resolution_m = 1.0;  // hdl_localization ndt_resolution
  double downsample_m = 0.1;      // hdl_localization downsample_resolution
};

}  // namespace bimloc::peers
