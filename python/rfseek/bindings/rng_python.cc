/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(rng.h) */
/* BINDTOOL_HEADER_FILE_HASH(7f9b0d6004011701d1d0606fca89c4bd) */

#include <gr-rfseek/rng.h>
#include <pybind11/pybind11.h>

namespace py = pybind11;

void bind_rng(py::module& m)
{
    using gr::rfseek::rng;
    py::class_<rng>(
        m, "rng", "Run-owned random source (xoshiro256**, seeded per stream).")
        .def(py::init<std::uint64_t, std::uint64_t, std::uint64_t>(),
             py::arg("seed"),
             py::arg("stream") = 0,
             py::arg("index") = 0,
             "A counter-based generator for (seed, stream, index): the same triple gives "
             "the same numbers on every platform.")
        .def("reseed",
             &rng::reseed,
             py::arg("seed"),
             py::arg("stream") = 0,
             py::arg("index") = 0,
             "Restart at (seed, stream, index).")
        .def("next", &rng::next, "Next raw 64-bit value.")
        .def("uniform", py::overload_cast<>(&rng::uniform), "Uniform in [0, 1).")
        .def("uniform",
             py::overload_cast<double, double>(&rng::uniform),
             py::arg("a"),
             py::arg("b"),
             "Uniform in [a, b).")
        .def("normal", &rng::normal, "Standard normal.");
}
