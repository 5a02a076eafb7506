// The sensor model that turns a probe series into what a pressure transducer would report,
// applied alike to simulated and measured series so that peaks are compared like for like.
//
// A series is a list of samples (t_k, y_k) at increasing times; sample k holds over
// (t_{k-1}, t_k] (a probe samples after each step, so its value stands for the step that
// led to it); the first sample holds over one preceding interval (t_0 - (t_1 - t_0), t_0].
//  1. Resampling to the experiment's rate f (Lobovsky et al. 2014: 20 kHz): the held
//     signal is averaged over each bin (j/f, (j+1)/f] of the absolute time grid, weighted
//     by time; the bin's sample is stamped at its end, (j+1)/f, so the result holds over
//     its bin like the input. Bins only partly covered by the signal average over the part
//     covered.
//  2. A centred moving average of width W (default 1 ms): the held resampled signal averaged
//     over [tau - W/2, tau + W/2] at each stamp tau, the window clipped to the signal's extent
//     at its two ends. With W a whole number of bins this is the mean of W f samples.
// Both steps are averages of a piecewise-constant signal, so a constant stays constant and a
// ramp stays a ramp (delayed by half a bin by the hold).
#pragma once

#include <vector>

namespace bsmpm {

struct SensorModel {
  double rate = 20000.0;  // resampling rate [Hz]
  double window = 1e-3;   // moving-average width [s]; 0: resample only
};

struct Series {
  std::vector<double> t;  // s, strictly increasing
  std::vector<double> y;
};

// Step 1: time-weighted bin averages at `rate`; throws std::invalid_argument on times that
// do not increase or a non-positive rate.
Series resample(const Series& raw, double rate);

// Step 2 on a series held sample by sample: centred moving average of width `window`.
Series moving_average(const Series& held, double window);

// Both steps.
Series apply_sensor_model(const Series& raw, const SensorModel& model);

}  // namespace bsmpm
