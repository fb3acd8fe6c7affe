/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(burst_detector.h) */
/* BINDTOOL_HEADER_FILE_HASH(e58db0843e83737f8768074fdf7b41a3) */

#include <gr-rfseek/burst_detector.h>
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

void bind_burst_detector(py::module& m)
{
    using gr::rfseek::burst_detector;
    py::class_<burst_detector>(
        m,
        "burst_detector",
        "Energy gating: burst starts from the power over the noise floor.")
        .def(py::init<double, std::uint64_t, int, int, int>(),
             py::arg("threshold_db") = 2.0,
             py::arg("holdoff") = 1000,
             py::arg("average_len") = 256,
             py::arg("floor_block") = 512,
             py::arg("floor_blocks") = 16,
             "A detector of bursts over a tracked noise floor (threshold in dB over it).")
        .def(
            "push",
            [](burst_detector& d,
               py::array_t<std::complex<float>, py::array::c_style | py::array::forcecast>
                   x,
               std::uint64_t offset) {
                std::vector<std::uint64_t> starts;
                d.push(x.data(), static_cast<std::size_t>(x.size()), offset, starts);
                return starts;
            },
            py::arg("x"),
            py::arg("offset"),
            "Feed samples (first at absolute index offset); returns the burst starts "
            "found.")
        .def("noise_floor",
             &burst_detector::noise_floor,
             "Current noise-floor estimate (mean power per sample; 0 before the first "
             "blocks).")
        .def("threshold_db",
             &burst_detector::threshold_db,
             "Detection level over the noise floor (dB).")
        .def("set_threshold_db",
             &burst_detector::set_threshold_db,
             py::arg("threshold_db"),
             "Change the detection level (dB, > 0).");
}
