/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(burst_acquirer.h) */
/* BINDTOOL_HEADER_FILE_HASH(c1ee8e7752fb8aba2ca6e4fd06cfcbd2) */

#include <gr-rfseek/burst_acquirer.h>
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace {
void bind_burst_acquirer_config(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<burst_acquirer_config>(
        m, "burst_acquirer_config", "Settings of burst_acquirer.")
        .def(py::init<>(), "Defaults: N = 1000 every 5000 samples, pfa 1e-3.")
        .def_readwrite("window_len",
                       &burst_acquirer_config::window_len,
                       "N, the burst length in samples (>= 16)")
        .def_readwrite("period",
                       &burst_acquirer_config::period,
                       "nominal samples from burst to burst (> window_len)")
        .def_readwrite("pfa",
                       &burst_acquirer_config::pfa,
                       "false-alarm probability of each window's test")
        .def_readwrite("min_freq_hz",
                       &burst_acquirer_config::min_freq_hz,
                       "search band's lower edge (equal edges: whole band)")
        .def_readwrite("max_freq_hz",
                       &burst_acquirer_config::max_freq_hz,
                       "search band's upper edge (equal edges: whole band)")
        .def_readwrite(
            "hop", &burst_acquirer_config::hop, "search step in samples (0: N / 4)")
        .def_readwrite("margin",
                       &burst_acquirer_config::margin,
                       "timing search +- samples (0: min(N / 4, (period - N) / 2))")
        .def_readwrite("max_misses",
                       &burst_acquirer_config::max_misses,
                       "undetected bursts in a row before searching again")
        .def_readwrite("loop_alpha",
                       &burst_acquirer_config::loop_alpha,
                       "timing loop: steady-state phase gain (0, 1]")
        .def_readwrite("loop_beta",
                       &burst_acquirer_config::loop_beta,
                       "timing loop: period gain [0, loop_alpha]")
        .def_readwrite("track_bins",
                       &burst_acquirer_config::track_bins,
                       "locked: search +- this many bins around the tracked tone (0: "
                       "the whole band)")
        .def_readwrite("max_carriers",
                       &burst_acquirer_config::max_carriers,
                       "continuous carriers removed (0: none, only rejected)");
}
} // namespace

void bind_burst_acquirer(py::module& m)
{
    using namespace gr::rfseek;
    bind_burst_acquirer_config(m);

    py::class_<acquired_window>(m, "acquired_window", "One beacon window.")
        .def(py::init<>(), "An empty window.")
        .def_readonly("start",
                      &acquired_window::start,
                      "absolute index of the window's first sample")
        .def_readonly("slot",
                      &acquired_window::slot,
                      "period number counted from the stream's first sample")
        .def_readonly(
            "detection", &acquired_window::detection, "the detection test of this window")
        .def_readonly("timing_error",
                      &acquired_window::timing_error,
                      "matched-filter start - predicted start (samples)")
        .def_readonly(
            "lock", &acquired_window::lock, "the acquisition it belongs to (1, 2, ...)")
        .def_readonly("min_freq_hz",
                      &acquired_window::min_freq_hz,
                      "the band its test searched around the tracked tone (equal "
                      "edges: the configured band)")
        .def_readonly(
            "max_freq_hz", &acquired_window::max_freq_hz, "the band's upper edge")
        .def_readonly("peak",
                      &acquired_window::peak,
                      "the largest |I| or |Q| of the samples as received")
        .def_property_readonly(
            "samples",
            [](const acquired_window& w) {
                return py::array_t<std::complex<float>>(w.samples.size(),
                                                        w.samples.data());
            },
            "the window_len samples from start (numpy complex64)");

    py::class_<burst_acquirer>(m,
                               "burst_acquirer",
                               "Burst timing for a pulsed beacon: narrowband search, "
                               "confirmation, a timing loop locked to the period.")
        .def(py::init<double, const burst_acquirer_config&>(),
             py::arg("samp_rate"),
             py::arg("config") = burst_acquirer_config(),
             "An acquirer at samp_rate (Hz) with the given settings.")
        .def(
            "push",
            [](burst_acquirer& a,
               py::array_t<std::complex<float>, py::array::c_style | py::array::forcecast>
                   x) {
                std::vector<acquired_window> out;
                a.push(x.data(), static_cast<std::size_t>(x.size()), out);
                return out;
            },
            py::arg("x"),
            "Feed the stream's next samples; returns the windows completed.")
        .def("state", &burst_acquirer::state_name, "'search', 'confirm' or 'locked'.")
        .def("period_estimate",
             &burst_acquirer::period_estimate,
             "The period the loop tracks (samples).")
        .def("acquisitions", &burst_acquirer::acquisitions, "Locks acquired so far.")
        .def("losses", &burst_acquirer::losses, "Locks lost so far.")
        .def("samples_seen", &burst_acquirer::samples_seen, "Samples pushed so far.")
        .def("gaps", &burst_acquirer::gaps, "Gaps told so far.")
        .def("carriers",
             &burst_acquirer::carriers,
             "The continuous carriers removed (Hz).")
        .def(
            "tracked_freq",
            &burst_acquirer::tracked_freq,
            "Locked and searching around the tracked tone: its frequency (Hz); else NaN.")
        .def("gap",
             &burst_acquirer::gap,
             py::arg("samples"),
             "Samples were lost after those pushed so far (an overflow): the lock goes "
             "on in time across the gap and must find one of the next two bursts.")
        .def("set_pfa", &burst_acquirer::set_pfa, py::arg("pfa"), "Change pfa.")
        .def("set_band",
             &burst_acquirer::set_band,
             py::arg("min_freq"),
             py::arg("max_freq"),
             "Search only [min, max] Hz (equal values: the whole band).")
        .def("set_samp_rate",
             &burst_acquirer::set_samp_rate,
             py::arg("samp_rate"),
             "A new sample rate (> 0; the band must still fit); timing is in samples "
             "and is kept.");
}
