/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(world.h) */
/* BINDTOOL_HEADER_FILE_HASH(e5b6c5082c4801050dab2ab9663497cc) */

#include <gr-rfseek/world.h>
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

void bind_world(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<scatterer>(m, "scatterer", "Point scatterer: position and Gamma_i.")
        .def_readonly("x_m", &scatterer::x_m)
        .def_readonly("y_m", &scatterer::y_m)
        .def_readonly("gamma", &scatterer::gamma);
    py::class_<path_state>(m, "path_state", "One path at the UAV (LOS first).")
        .def_readonly("amplitude", &path_state::amplitude)
        .def_readonly("doppler_hz", &path_state::doppler_hz)
        .def_readonly("length_m", &path_state::length_m);

    py::class_<world>(
        m, "world", "The simulated physics of one run, slot by slot (paper eq. 1-2).")
        .def(py::init<const scenario&>(), py::arg("scenario"))
        .def_property_readonly("config", &world::config)
        .def_property_readonly("scatterers", &world::scatterers)
        .def_property_readonly("slot", &world::slot)
        .def_property_readonly("time_s", &world::time_s)
        .def_property_readonly("x_m", &world::x_m)
        .def_property_readonly("y_m", &world::y_m)
        .def_property_readonly("heading_rad", &world::heading_rad)
        .def_property_readonly("measured_heading_rad", &world::measured_heading_rad)
        .def_property_readonly("distance_m", &world::distance_m)
        .def_property_readonly("distance_flown_m", &world::distance_flown_m)
        .def_property_readonly("straight_air_m", &world::straight_air_m)
        .def_property_readonly("wind_east_mps", &world::wind_east_mps)
        .def_property_readonly("wind_north_mps", &world::wind_north_mps)
        .def_property_readonly("bearing_to_emitter_rad", &world::bearing_to_emitter_rad)
        .def_property_readonly("cfo_hz", &world::cfo_hz)
        .def_property_readonly("cfo_drift_hz_per_s", &world::cfo_drift_hz_per_s)
        .def_property_readonly("los_doppler_hz", &world::los_doppler_hz)
        .def_property_readonly("slant_range_m", &world::slant_range_m)
        .def_property_readonly("ground_vx_mps", &world::ground_vx_mps)
        .def_property_readonly("ground_vy_mps", &world::ground_vy_mps)
        .def_property_readonly("compass_error_rad", &world::compass_error_rad)
        .def_property_readonly("amplitude_scale", &world::amplitude_scale)
        .def_property_readonly("noise_power", &world::noise_power)
        .def_property_readonly("arrived", &world::arrived)
        .def_property_readonly("capped", &world::capped)
        .def_property_readonly("reached", &world::reached)
        .def_property_readonly("reached_flown_m", &world::reached_flown_m)
        .def_property_readonly("ended", &world::ended)
        .def("end_run",
             &world::end_run,
             "End the run now (the vehicle declared it is done).")
        .def_property_readonly("finished", &world::finished)
        .def("field", &world::field, "Eq. 2 at the UAV (1/m).")
        .def("paths", &world::paths)
        .def("received_power", &world::received_power)
        .def("mean_power_at", &world::mean_power_at, py::arg("distance_m"))
        .def("snr_db", &world::snr_db)
        .def(
            "synthesize",
            [](const world& w, std::size_t n) {
                py::array_t<std::complex<float>> a(n);
                w.synthesize(a.mutable_data(), n);
                return a;
            },
            py::arg("n"),
            "n samples of this slot (beacon first) as complex64.")
        .def("advance", &world::advance, py::arg("commanded_heading_rad"))
        .def("set_snr_db", &world::set_snr_db, py::arg("snr_db"))
        .def("set_heading_noise_rad", &world::set_heading_noise_rad, py::arg("sigma"))
        .def("set_turn_rate_rad_per_s", &world::set_turn_rate_rad_per_s, py::arg("rate"))
        .def_static("wrap", &world::wrap, py::arg("angle"));
}
