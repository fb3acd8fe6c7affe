/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(arrival.h) */
/* BINDTOOL_HEADER_FILE_HASH(79d85a911938245822721c334218f8af) */

#include <gr-rfseek/arrival.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

void bind_arrival(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<overflight_config>(m, "overflight_config", "Overflight detector settings.")
        .def(py::init<>())
        .def_readwrite("max_doppler_hz", &overflight_config::max_doppler_hz)
        .def_readwrite("slot_period_s", &overflight_config::slot_period_s)
        .def_readwrite("swing", &overflight_config::swing)
        .def_readwrite("window_s", &overflight_config::window_s)
        .def_readwrite("heading_band_rad", &overflight_config::heading_band_rad)
        .def_readwrite("power_rise_db", &overflight_config::power_rise_db)
        .def_readwrite("drift_s", &overflight_config::drift_s)
        .def_readwrite("block_slots", &overflight_config::block_slots)
        .def_readwrite("confirm_blocks", &overflight_config::confirm_blocks)
        .def_readwrite("min_snr_db", &overflight_config::min_snr_db)
        .def_readwrite("encircle_amplitude", &overflight_config::encircle_amplitude);

    py::class_<doppler_amplitude>(
        m,
        "doppler_amplitude",
        "The Doppler amplitude of a turn: hypot(p, q) of c + d t + p cos(psi) + q "
        "sin(psi) fitted robustly; f_d,max far from the emitter, much less near it.")
        .def(py::init<>())
        .def("add",
             &doppler_amplitude::add,
             py::arg("time_s"),
             py::arg("heading_rad"),
             py::arg("freq_hz"))
        .def("clear", &doppler_amplitude::clear)
        .def("__len__", &doppler_amplitude::size)
        .def_property_readonly("amplitude", &doppler_amplitude::amplitude);

    py::class_<overflight_detector>(
        m,
        "overflight_detector",
        "The overflight signature: the Doppler swings toward -f_d,max at a steady "
        "heading while the power peaks; or the encircling one: headings all round, the "
        "far-field Doppler amplitude collapsed.")
        .def(py::init<const overflight_config&>(),
             py::arg("config") = overflight_config())
        .def("update",
             &overflight_detector::update,
             py::arg("time_s"),
             py::arg("freq_hz"),
             py::arg("power_db"),
             py::arg("snr_db"),
             py::arg("valid"),
             py::arg("heading_rad"))
        .def_property_readonly("detected", &overflight_detector::detected)
        .def_property_readonly("detect_time_s", &overflight_detector::detect_time_s)
        .def_property_readonly("last_drop_hz", &overflight_detector::last_drop_hz)
        .def_property_readonly("last_amplitude_hz",
                               &overflight_detector::last_amplitude_hz)
        .def_property_readonly("encircled", &overflight_detector::encircled)
        .def("reset", &overflight_detector::reset);

    py::class_<emitter_location>(
        m, "emitter_location", "A location fix (docs/seeker.md).")
        .def(py::init<>())
        .def_readonly("valid", &emitter_location::valid)
        .def_readonly("time_s", &emitter_location::time_s)
        .def_readonly("east_m", &emitter_location::east_m)
        .def_readonly("north_m", &emitter_location::north_m)
        .def_readonly("dr_x_m", &emitter_location::dr_x_m)
        .def_readonly("dr_y_m", &emitter_location::dr_y_m)
        .def_readonly("major_m", &emitter_location::major_m)
        .def_readonly("minor_m", &emitter_location::minor_m)
        .def_readonly("major_angle_rad", &emitter_location::major_angle_rad)
        .def_readonly("wind_east_mps", &emitter_location::wind_east_mps)
        .def_readonly("wind_north_mps", &emitter_location::wind_north_mps)
        .def_readonly("wind_sigma_mps", &emitter_location::wind_sigma_mps)
        .def_readonly("altitude_m", &emitter_location::altitude_m)
        .def_readonly("cfo_hz", &emitter_location::cfo_hz)
        .def_readonly("rms_hz", &emitter_location::rms_hz)
        .def_readonly("used", &emitter_location::used)
        .def_readonly("inflation", &emitter_location::inflation)
        .def_readonly("gust_knots", &emitter_location::gust_knots);

    py::class_<emitter_locator>(
        m, "emitter_locator", "The emitter from the Doppler along a dead-reckoned path.")
        .def(py::init<double, double, double, double, double, double>(),
             py::arg("wavelength_m"),
             py::arg("search_radius_m") = 600.0,
             py::arg("gust_mps") = 0.0,
             py::arg("gust_tau_s") = 5.0,
             py::arg("altitude_m") = 0.0,
             py::arg("altitude_sigma_m") = 0.0)
        .def("add",
             &emitter_locator::add,
             py::arg("time_s"),
             py::arg("x_m"),
             py::arg("y_m"),
             py::arg("vx_mps"),
             py::arg("vy_mps"),
             py::arg("freq_hz"))
        .def("__len__", &emitter_locator::size)
        .def("clear", &emitter_locator::clear)
        .def("fit",
             &emitter_locator::fit,
             py::arg("vehicle_x_m"),
             py::arg("vehicle_y_m"),
             py::call_guard<py::gil_scoped_release>());
}
