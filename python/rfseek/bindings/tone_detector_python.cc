/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(tone_detector.h) */
/* BINDTOOL_HEADER_FILE_HASH(74541d82f31f96828d80d881f5c7152b) */

#include <gr-rfseek/tone_detector.h>
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <stdexcept>

namespace py = pybind11;

void bind_tone_detector(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<tone_detection>(m, "tone_detection", "One window's detection.")
        .def(py::init<>(), "An empty detection (not detected).")
        .def_readonly("g",
                      &tone_detection::g,
                      "statistic: largest in-band periodogram share (0..1)")
        .def_readonly("threshold",
                      &tone_detection::threshold,
                      "g above which the window holds a tone")
        .def_readonly("margin_db",
                      &tone_detection::margin_db,
                      "10 log10(g / threshold): > 0 when detected")
        .def_readonly("freq_hz",
                      &tone_detection::freq_hz,
                      "frequency of the largest in-band bin (coarse)")
        .def_readonly("detected", &tone_detection::detected, "g > threshold")
        .def("__repr__", [](const tone_detection& d) {
            return "tone_detection(g=" + std::to_string(d.g) +
                   ", threshold=" + std::to_string(d.threshold) +
                   ", freq_hz=" + std::to_string(d.freq_hz) +
                   ", detected=" + (d.detected ? "True" : "False") + ")";
        });

    py::class_<tone_detector>(m,
                              "tone_detector",
                              "Is there a tone in this window? Fisher's g test at a set "
                              "false-alarm probability.")
        .def(py::init<double, int, double, double, double>(),
             py::arg("samp_rate"),
             py::arg("window_len"),
             py::arg("pfa") = 1e-3,
             py::arg("min_freq") = 0.0,
             py::arg("max_freq") = 0.0,
             "\\param samp_rate sample rate (> 0) \\param window_len N (16 <= N <= 2^22) "
             "\\param pfa false-alarm probability per window (1e-12 <= pfa <= 0.5) "
             "\\param min_freq, max_freq search band; equal values search the whole band")
        .def(
            "test",
            [](tone_detector& d,
               py::array_t<std::complex<float>, py::array::c_style | py::array::forcecast>
                   x) {
                if (x.ndim() != 1 || x.size() != d.window_len())
                    throw py::value_error(
                        "tone_detector.test: x must hold window_len = " +
                        std::to_string(d.window_len()) + " samples");
                return d.test(x.data());
            },
            py::arg("x"),
            "Test window_len samples. Zero, NaN or Inf input is never detected.")
        .def("samp_rate", &tone_detector::samp_rate_hz, "Sample rate (Hz).")
        .def("window_len", &tone_detector::window_len, "N, samples per window.")
        .def("pfa", &tone_detector::pfa, "False-alarm probability per window.")
        .def("min_freq", &tone_detector::min_freq_hz, "Lower edge of the band (Hz).")
        .def("max_freq", &tone_detector::max_freq_hz, "Upper edge of the band (Hz).")
        .def("band_bins",
             &tone_detector::band_bins,
             "Bins of one set (N-point DFT) in the search band.")
        .def("threshold", &tone_detector::threshold, "The g threshold (2 P1 = pfa).")
        .def("set_pfa", &tone_detector::set_pfa, py::arg("pfa"), "Change pfa.")
        .def("set_band",
             &tone_detector::set_band,
             py::arg("min_freq"),
             py::arg("max_freq"),
             "Search only [min, max] Hz (equal values: the whole band).")
        .def("set_samp_rate",
             &tone_detector::set_samp_rate,
             py::arg("samp_rate"),
             "A new sample rate (> 0; the band in Hz is kept and must still fit). "
             "ValueError, with nothing changed, otherwise.")
        .def_static("set_false_alarm",
                    &tone_detector::set_false_alarm,
                    py::arg("x"),
                    py::arg("window_len"),
                    py::arg("band_bins"),
                    "P1(x): probability that the largest of B of N uniform-spacing "
                    "shares exceeds x (one set of bins, noise only).")
        .def_static("threshold_for",
                    &tone_detector::threshold_for,
                    py::arg("pfa"),
                    py::arg("window_len"),
                    py::arg("band_bins"),
                    "The x that solves 2 P1(x) = pfa.");
}
