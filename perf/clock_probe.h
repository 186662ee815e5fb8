// The GPU's clock around timed frames. A GPU lowers its clocks when lightly loaded: an H100
// rendering 128x72 radiance-cache frames (busy 20-30%) went from 1980 to ~360 MHz SM clock over
// ~5 s (nvidia-smi, sampled every 100 ms), and the same frame read 0.48 ms early in `gibench
// timing` and 1.83 ms four repeats later; 100 ms of saturating probe dispatches before the timed
// frames did not bring the clock back. So the probe does not hold the clock; it measures it: a
// fixed FMA dispatch timed right before and right after the timed frames, against the fastest
// the same dispatch ran on this device in this process (the first ones run at the boost clock).
// A ratio of 1 says the frames ran at the fastest clock this process saw, 3 that their times may
// be inflated up to 3x (a lower bound when the process never saw the peak). Checked on an H100,
// `gibench timing` of thin-wall-leak-005 at 128x72, 4 repeats: run's ratio 1.00 / 1.97 / 3.12 /
// 3.52 as its frame median went 0.72 / 1.26 / 1.77 / 1.89 ms and nvidia-smi's SM clock fell
// 1980 -> 345 MHz. Nothing in the device's settings is changed. On a CPU device there is
// nothing to probe.
#pragma once
#include <memory>
#include <nlohmann/json.hpp>

#include "renderer/vk/gpu.h"

namespace gib::perf {

struct ClockCheck {
  double fastest_probe_ms = 0;  // the probe's fastest time on this device in this process
  double before_probe_ms = 0;   // right before the timed frames
  double after_probe_ms = 0;    // right after them
  bool measured() const { return fastest_probe_ms > 0 && before_probe_ms > 0 && after_probe_ms > 0; }
  // How much slower than its fastest the probe ran around the frames (the worse of the two).
  double ratio() const;
  nlohmann::json to_json() const;  // the three times and the ratio, for results and timing JSON
};

class ClockProbe {
 public:
  // Builds the probe kernel (perf/calibrate_fma.comp) and sizes it to ~0.2 ms on this device.
  explicit ClockProbe(Gpu& gpu);
  ~ClockProbe();
  double probe();          // one dispatch, ms; also updates the device's fastest
  double fastest() const;  // this probe's size at the fastest rate seen on this device, ms

 private:
  struct State;
  Gpu& gpu_;
  std::unique_ptr<State> s_;
};

}  // namespace gib::perf
