/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(simulation.h) */
/* BINDTOOL_HEADER_FILE_HASH(e356956dd29d1f1daa38d1fc660b88cc) */

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

namespace {

void bind_estimator_config_class(py::module& m)
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
            py::arg("max_freq_hz") = 0.0,
            "How the frequency is measured in the loop: window, interpolator, search "
            "band (Hz; equal edges: the whole band).")
        .def_readwrite("window", &estimator_config::window, "The window's name.")
        .def_readwrite("interpolator",
                       &estimator_config::interpolator,
                       "The peak interpolator's name.")
        .def_readwrite("min_freq_hz",
                       &estimator_config::min_freq_hz,
                       "Lower edge of the search band (Hz).")
        .def_readwrite("max_freq_hz",
                       &estimator_config::max_freq_hz,
                       "Upper edge of the search band (Hz).");
}

void bind_run_summary_class(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<run_summary>(m,
                            "run_summary",
                            "What one run achieved: distance, ratio, time, success, and "
                            "with self_arrival the arrival and location figures.")
        .def_readonly("strategy", &run_summary::strategy, "The strategy flown.")
        .def_readonly("seed", &run_summary::seed, "The scenario seed.")
        .def_readonly(
            "distance_m", &run_summary::distance_m, "flown, Stage-1 circle included")
        .def_readonly("shortest_path_m", &run_summary::shortest_path_m, "d - d_v")
        .def_readonly("ratio", &run_summary::ratio, "distance_m / shortest_path_m")
        .def_readonly(
            "straight_air_m",
            &run_summary::straight_air_m,
            "Air distance of the straight ground line to d_v in the mean wind at the "
            "start (world::straight_air_m; shortest_path_m in calm air).")
        .def_readonly("straight_ratio",
                      &run_summary::straight_ratio,
                      "distance_m / straight_air_m: 1 for the straight ground track "
                      "whatever the wind (ratio in calm air; 0 when the wind blows "
                      "faster than the airspeed against it).")
        .def_readonly(
            "time_s", &run_summary::time_s, "Flight time to arrival or the cap (s).")
        .def_readonly(
            "success", &run_summary::success, "arrived within d_v before the flight cap")
        .def_readonly("slots", &run_summary::slots, "Slots flown.")
        .def_readonly("has_stage1",
                      &run_summary::has_stage1,
                      "Stage 1 decided a heading (paper's strategies).")
        .def_readonly("stage1_heading_error_rad",
                      &run_summary::stage1_heading_error_rad,
                      "theta_0 minus the true bearing, at the decision")
        .def_readonly("updates", &run_summary::updates, "Stage-2 updates applied")
        .def_readonly("self_arrival",
                      &run_summary::self_arrival,
                      "Arrival was decided by the vehicle (scenario.self_arrival).")
        .def_readonly(
            "overflight",
            &run_summary::overflight,
            "The overflight (or encircling) signature was first seen (the loiter began).")
        .def_readonly("overflight_distance_m",
                      &run_summary::overflight_distance_m,
                      "true horizontal distance then")
        .def_readonly(
            "declared",
            &run_summary::declared,
            "The vehicle declared its arrival (seeker_config::arrival_confirm_m: when a "
            "location fit confirmed it; 0: at the overflight).")
        .def_readonly("arrival_time_s",
                      &run_summary::arrival_time_s,
                      "When the vehicle declared its arrival (s).")
        .def_readonly("arrival_detect_distance_m",
                      &run_summary::arrival_detect_distance_m,
                      "true horizontal distance then")
        .def_readonly(
            "false_arrival", &run_summary::false_arrival, "declared more than 1 km away")
        .def_readonly("located", &run_summary::located, "a location fix was published")
        .def_readonly("location_error_m",
                      &run_summary::location_error_m,
                      "|estimated - true| emitter offset at the fix")
        .def_readonly("location_major_m",
                      &run_summary::location_major_m,
                      "95 % ellipse semi-axes of the fix")
        .def_readonly("location_minor_m",
                      &run_summary::location_minor_m,
                      "95 % ellipse semi-minor axis of the fix (m).")
        .def_readonly("location_in_ellipse",
                      &run_summary::location_in_ellipse,
                      "the truth lies inside the 95 % ellipse")
        .def_readonly("location_in_ellipse50",
                      &run_summary::location_in_ellipse50,
                      "the truth lies inside the 50 % ellipse")
        .def_readonly("location_unsure",
                      &run_summary::location_unsure,
                      "the fix was published unsure (its 95 % ellipse larger than "
                      "locate_max_axis_m when the loiter's budget ran out)")
        .def_readonly("total_distance_m",
                      &run_summary::total_distance_m,
                      "flown until the run ended (loiter included)");
}

void bind_slot_record_class(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<slot_record>(
        m, "slot_record", "Truth, measurement and decision of one slot.")
        .def_readonly("slot", &slot_record::slot, "Slot index.")
        .def_readonly(
            "time_s", &slot_record::time_s, "Time at the start of the slot (s).")
        .def_readonly("x_m", &slot_record::x_m, "UAV east position (m).")
        .def_readonly("y_m", &slot_record::y_m, "UAV north position (m).")
        .def_readonly(
            "heading_rad", &slot_record::heading_rad, "true heading at the beacon")
        .def_readonly("measured_heading_rad",
                      &slot_record::measured_heading_rad,
                      "what the seeker was told")
        .def_readonly("distance_m", &slot_record::distance_m, "to the emitter")
        .def_readonly("distance_flown_m",
                      &slot_record::distance_flown_m,
                      "Air distance flown so far (m).")
        .def_readonly("cfo_hz", &slot_record::cfo_hz, "truth")
        .def_readonly("doppler_hz", &slot_record::doppler_hz, "LOS Doppler (truth)")
        .def_readonly(
            "true_snr_db", &slot_record::true_snr_db, "instantaneous SNR (truth)")
        .def_readonly("freq_hz", &slot_record::freq_hz, "measured")
        .def_readonly("snr_db", &slot_record::snr_db, "estimated")
        .def_readonly("power_db", &slot_record::power_db, "estimated tone power")
        .def_readonly("valid", &slot_record::valid, "The measurement was valid.")
        .def_readonly("stage", &slot_record::stage, "The seeker's stage.")
        .def_readonly("theta_est_rad",
                      &slot_record::theta_est_rad,
                      "The seeker's bearing estimate (rad).")
        .def_readonly("cmd_heading_rad",
                      &slot_record::cmd_heading_rad,
                      "The heading commanded for the next slot (rad).")
        .def_readonly(
            "update", &slot_record::update, "A Stage-2 update was applied in this slot.")
        .def_readonly("status",
                      &slot_record::status,
                      "0 seeking, 1 arrived (loitering), 2 located (self_arrival)");
}

void bind_run_result_class(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<run_result>(
        m,
        "run_result",
        "A run: its summary, the slots' records, the scene and the first fix.")
        .def_readonly("summary", &run_result::summary, "The run's run_summary.")
        .def_readonly(
            "records", &run_result::records, "Every slot's slot_record (when kept).")
        .def_readonly("scatterers", &run_result::scatterers, "The scatterers of the run.")
        .def_readonly("location",
                      &run_result::location,
                      "self_arrival: the first fix and where the vehicle truly was then.")
        .def_readonly("location_vehicle_x_m",
                      &run_result::location_vehicle_x_m,
                      "True vehicle east position at the first fix (m).")
        .def_readonly("location_vehicle_y_m",
                      &run_result::location_vehicle_y_m,
                      "True vehicle north position at the first fix (m).")
        .def("columns", &record_columns, "Per-slot records as a dict of numpy arrays.");
}

void bind_simulation_class(py::module& m)
{
    using namespace gr::rfseek;
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

} // namespace

void bind_simulation(py::module& m)
{
    bind_estimator_config_class(m);
    bind_run_summary_class(m);
    bind_slot_record_class(m);
    bind_run_result_class(m);
    bind_simulation_class(m);
}
