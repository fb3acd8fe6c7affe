/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(simulation.h) */
/* BINDTOOL_HEADER_FILE_HASH(c101f784d1edf4c818ba165a3a983a02) */

#include <gr-rfseek/simulation.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace {

// The per-slot records as a dict of numpy arrays (for plots).
py::dict record_columns(const gr::rfseek::run_result& r)
{
    using gr::rfseek::slot_record;
    const auto& v = r.records;
    py::dict d;
    auto col = [&](const char* name, auto getter) {
        py::array_t<double> a(v.size());
        auto* p = a.mutable_data();
        for (std::size_t i = 0; i < v.size(); ++i)
            p[i] = static_cast<double>(getter(v[i]));
        d[name] = a;
    };
    col("slot", [](const slot_record& s) { return s.slot; });
    col("time_s", [](const slot_record& s) { return s.time_s; });
    col("x_m", [](const slot_record& s) { return s.x_m; });
    col("y_m", [](const slot_record& s) { return s.y_m; });
    col("heading_rad", [](const slot_record& s) { return s.heading_rad; });
    col("measured_heading_rad",
        [](const slot_record& s) { return s.measured_heading_rad; });
    col("distance_m", [](const slot_record& s) { return s.distance_m; });
    col("distance_flown_m", [](const slot_record& s) { return s.distance_flown_m; });
    col("cfo_hz", [](const slot_record& s) { return s.cfo_hz; });
    col("doppler_hz", [](const slot_record& s) { return s.doppler_hz; });
    col("true_snr_db", [](const slot_record& s) { return s.true_snr_db; });
    col("freq_hz", [](const slot_record& s) { return s.freq_hz; });
    col("snr_db", [](const slot_record& s) { return s.snr_db; });
    col("power_db", [](const slot_record& s) { return s.power_db; });
    col("valid", [](const slot_record& s) { return s.valid; });
    col("stage", [](const slot_record& s) { return s.stage; });
    col("theta_est_rad", [](const slot_record& s) { return s.theta_est_rad; });
    col("cmd_heading_rad", [](const slot_record& s) { return s.cmd_heading_rad; });
    col("update", [](const slot_record& s) { return s.update; });
    col("status", [](const slot_record& s) { return s.status; });
    return d;
}

} // namespace

void bind_simulation(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<estimator_config>(
        m, "estimator_config", "tone_estimator settings in the loop.")
        .def(
            py::init([](const std::string& window,
                        const std::string& interpolator,
                        double min_freq_hz,
                        double max_freq_hz) {
                return estimator_config{ window, interpolator, min_freq_hz, max_freq_hz };
            }),
            py::arg("window") = "rectangular",
            py::arg("interpolator") = "parabolic",
            py::arg("min_freq_hz") = 0.0,
            py::arg("max_freq_hz") = 0.0)
        .def_readwrite("window", &estimator_config::window)
        .def_readwrite("interpolator", &estimator_config::interpolator)
        .def_readwrite("min_freq_hz", &estimator_config::min_freq_hz)
        .def_readwrite("max_freq_hz", &estimator_config::max_freq_hz);

    py::class_<run_summary>(m, "run_summary")
        .def_readonly("strategy", &run_summary::strategy)
        .def_readonly("seed", &run_summary::seed)
        .def_readonly("distance_m", &run_summary::distance_m)
        .def_readonly("shortest_path_m", &run_summary::shortest_path_m)
        .def_readonly("ratio", &run_summary::ratio)
        .def_readonly("straight_air_m", &run_summary::straight_air_m)
        .def_readonly("straight_ratio", &run_summary::straight_ratio)
        .def_readonly("time_s", &run_summary::time_s)
        .def_readonly("success", &run_summary::success)
        .def_readonly("slots", &run_summary::slots)
        .def_readonly("has_stage1", &run_summary::has_stage1)
        .def_readonly("stage1_heading_error_rad", &run_summary::stage1_heading_error_rad)
        .def_readonly("updates", &run_summary::updates)
        .def_readonly("self_arrival", &run_summary::self_arrival)
        .def_readonly("overflight", &run_summary::overflight)
        .def_readonly("overflight_distance_m", &run_summary::overflight_distance_m)
        .def_readonly("declared", &run_summary::declared)
        .def_readonly("arrival_time_s", &run_summary::arrival_time_s)
        .def_readonly("arrival_detect_distance_m",
                      &run_summary::arrival_detect_distance_m)
        .def_readonly("false_arrival", &run_summary::false_arrival)
        .def_readonly("located", &run_summary::located)
        .def_readonly("location_error_m", &run_summary::location_error_m)
        .def_readonly("location_major_m", &run_summary::location_major_m)
        .def_readonly("location_minor_m", &run_summary::location_minor_m)
        .def_readonly("location_in_ellipse", &run_summary::location_in_ellipse)
        .def_readonly("total_distance_m", &run_summary::total_distance_m);

    py::class_<slot_record>(m, "slot_record")
        .def_readonly("slot", &slot_record::slot)
        .def_readonly("time_s", &slot_record::time_s)
        .def_readonly("x_m", &slot_record::x_m)
        .def_readonly("y_m", &slot_record::y_m)
        .def_readonly("heading_rad", &slot_record::heading_rad)
        .def_readonly("measured_heading_rad", &slot_record::measured_heading_rad)
        .def_readonly("distance_m", &slot_record::distance_m)
        .def_readonly("distance_flown_m", &slot_record::distance_flown_m)
        .def_readonly("cfo_hz", &slot_record::cfo_hz)
        .def_readonly("doppler_hz", &slot_record::doppler_hz)
        .def_readonly("true_snr_db", &slot_record::true_snr_db)
        .def_readonly("freq_hz", &slot_record::freq_hz)
        .def_readonly("snr_db", &slot_record::snr_db)
        .def_readonly("power_db", &slot_record::power_db)
        .def_readonly("valid", &slot_record::valid)
        .def_readonly("stage", &slot_record::stage)
        .def_readonly("theta_est_rad", &slot_record::theta_est_rad)
        .def_readonly("cmd_heading_rad", &slot_record::cmd_heading_rad)
        .def_readonly("update", &slot_record::update)
        .def_readonly("status", &slot_record::status);

    py::class_<run_result>(m, "run_result")
        .def_readonly("summary", &run_result::summary)
        .def_readonly("records", &run_result::records)
        .def_readonly("scatterers", &run_result::scatterers)
        .def_readonly("location", &run_result::location)
        .def_readonly("location_vehicle_x_m", &run_result::location_vehicle_x_m)
        .def_readonly("location_vehicle_y_m", &run_result::location_vehicle_y_m)
        .def("columns", &record_columns, "Per-slot records as a dict of numpy arrays.");

    py::class_<simulation>(
        m,
        "simulation",
        "world + tone_estimator + seeker in a closed loop, no scheduler.")
        .def(py::init<const scenario&, const seeker_config&, const estimator_config&>(),
             py::arg("scenario"),
             py::arg("seeker_config"),
             py::arg("estimator_config") = estimator_config(),
             "The loop of a scenario, a seeker configuration and the estimator's "
             "settings (all validated: ValueError names the field).")
        .def("run",
             &simulation::run,
             py::arg("keep_records") = true,
             py::call_guard<py::gil_scoped_release>(),
             "Fly to arrival or the flight cap; a run_result (summary, and every slot's "
             "record when keep_records). The same seed gives the same run.")
        .def("scenario_config", &simulation::scenario_config, "The scenario it flies.")
        .def("seeker_cfg", &simulation::seeker_cfg, "The seeker configuration it flies.")
        .def_static("seeker_for",
                    &simulation::seeker_for,
                    py::arg("scenario"),
                    py::arg("strategy"),
                    "A seeker_config for the scenario: its speed, carrier, slot period, "
                    "turn rate and seed, the paper's constants otherwise.");
}
