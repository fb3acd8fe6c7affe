/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(tone_estimator.h) */
/* BINDTOOL_HEADER_FILE_HASH(0ebedec56c9ea21d0959705be835ea69) */

#include <gr-rfseek/tone_estimator.h>
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

void bind_tone_estimator(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<tone_estimate>(m, "tone_estimate", "One window's estimate.")
        .def(py::init<>(), "An empty estimate (invalid).")
        .def_readonly(
            "freq_hz", &tone_estimate::freq_hz, "tone frequency in (-fs/2, fs/2]")
        .def_readonly("snr_db",
                      &tone_estimate::snr_db,
                      "per-sample SNR of the tone against the rest of the window")
        .def_readonly("power_db",
                      &tone_estimate::power_db,
                      "tone power per sample (10 log10 |a|^2)")
        .def_readonly("noise_power_db",
                      &tone_estimate::noise_power_db,
                      "noise power per sample (window energy not in the tone)")
        .def_readonly("peak_bin", &tone_estimate::peak_bin, "FFT bin of the coarse peak")
        .def_readonly("valid",
                      &tone_estimate::valid,
                      "false on zero, NaN or Inf input, an empty band, or an estimate "
                      "outside the band")
        .def("__repr__", [](const tone_estimate& e) {
            return "tone_estimate(freq_hz=" + std::to_string(e.freq_hz) +
                   ", snr_db=" + std::to_string(e.snr_db) +
                   ", power_db=" + std::to_string(e.power_db) +
                   ", valid=" + (e.valid ? "True" : "False") + ")";
        });

    py::class_<tone_estimator>(
        m,
        "tone_estimator",
        "Frequency, SNR and power of the strongest tone in a window "
        "(zero-padded FFT peak + interpolation).")
        .def(py::init<double,
                      int,
                      int,
                      const std::string&,
                      const std::string&,
                      double,
                      double>(),
             py::arg("samp_rate"),
             py::arg("window_len"),
             py::arg("fft_len"),
             py::arg("window") = "rectangular",
             py::arg("interpolator") = "parabolic",
             py::arg("min_freq") = 0.0,
             py::arg("max_freq") = 0.0,
             "The estimator of a window of window_len samples: window, zero-padded FFT "
             "of fft_len, peak interpolation; ValueError names a bad parameter.")
        .def(
            "estimate",
            [](tone_estimator& e,
               py::array_t<std::complex<float>, py::array::c_style | py::array::forcecast>
                   x) {
                if (x.ndim() != 1 || x.shape(0) < e.window_len())
                    throw py::value_error(
                        "estimate: need a 1-D array of at least window_len = " +
                        std::to_string(e.window_len()) + " samples");
                return e.estimate(x.data());
            },
            py::arg("x"),
            "Estimate from window_len() samples at x.")
        .def_property_readonly(
            "samp_rate", &tone_estimator::samp_rate_hz, "Sample rate (Hz).")
        .def_property_readonly(
            "window_len", &tone_estimator::window_len, "N: samples per estimate.")
        .def_property_readonly(
            "fft_len", &tone_estimator::fft_len, "N_FFT: zero-padded FFT length.")
        .def("window", &tone_estimator::window, "The window's name.")
        .def("interpolator",
             &tone_estimator::interpolator,
             "The peak interpolator's name.")
        .def("min_freq",
             &tone_estimator::min_freq_hz,
             "Lower edge of the search band (Hz; equal edges: the whole band).")
        .def("max_freq",
             &tone_estimator::max_freq_hz,
             "Upper edge of the search band (Hz).")
        .def("set_window",
             &tone_estimator::set_window,
             py::arg("window"),
             "Change the window (one of windows()).")
        .def("set_interpolator",
             &tone_estimator::set_interpolator,
             py::arg("interpolator"),
             "Change the peak interpolator (one of interpolators()).")
        .def("set_band",
             &tone_estimator::set_band,
             py::arg("min_freq"),
             py::arg("max_freq"),
             "Search only [min, max] Hz (equal values: the whole band).")
        .def("set_samp_rate",
             &tone_estimator::set_samp_rate,
             py::arg("samp_rate"),
             "A new sample rate (> 0; the band in Hz is kept and must still fit). "
             "ValueError, with nothing changed, otherwise.")
        .def_static("windows", &tone_estimator::windows, "The window names.")
        .def_static(
            "interpolators",
            &tone_estimator::interpolators,
            "The peak interpolator names (parabolic: the paper's eq. 3; log_parabolic; "
            "newton: maximum likelihood, at the Cramer-Rao bound).")
        .def_static("crb_std_hz",
                    &tone_estimator::crb_std_hz,
                    py::arg("snr_linear"),
                    py::arg("window_len"),
                    py::arg("samp_rate"),
                    "Cramer-Rao bound on the frequency's standard deviation (Hz) for a "
                    "tone of per-sample SNR snr_linear in N samples: var = 6 / ((2 pi)^2 "
                    "SNR N (N^2 - 1) Ts^2).");
}
