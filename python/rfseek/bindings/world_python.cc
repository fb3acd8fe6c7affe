/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(world.h) */
/* BINDTOOL_HEADER_FILE_HASH(04362874d32c631b73cf66e1311de7ed) */

#include <gr-rfseek/world.h>
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace {

// The world's methods (its state's properties are bound in bind_world).
void bind_world_methods(py::class_<gr::rfseek::world>& w)
{
    using namespace gr::rfseek;
    w.def(
         "end_run", &world::end_run, "End the run now (the vehicle declared it is done).")
        .def_property_readonly("finished",
                               &world::finished,
                               "The run is over: arrived (without self_arrival), capped, "
                               "or ended by the vehicle.")
        .def("field", &world::field, "Eq. 2 at the UAV (1/m).")
        .def(
            "paths", &world::paths, "Every path (LOS first, then scatterers) at the UAV.")
        .def("received_power",
             &world::received_power,
             "Received beacon power A^2 |EF|^2 at the UAV (W, per sample).")
        .def("mean_power_at",
             &world::mean_power_at,
             py::arg("distance_m"),
             "Mean received power at distance d over positions and fading (no cross "
             "terms).")
        .def("snr_db",
             &world::snr_db,
             "Instantaneous per-sample SNR of this slot's beacon (dB).")
        .def(
            "synthesize",
            [](const world& w, std::size_t n) {
                py::array_t<std::complex<float>> a(n);
                w.synthesize(a.mutable_data(), n);
                return a;
            },
            py::arg("n"),
            "n samples of this slot (beacon first) as complex64.")
        .def("advance",
             &world::advance,
             py::arg("commanded_heading_rad"),
             "Fly one slot toward commanded_heading_rad (turning at most at the turn "
             "rate), advance the CFO, then draw the next slot's measured heading. Throws "
             "ValueError on a non-finite heading, RuntimeError once "
             "finished.")
        .def("set_snr_db",
             &world::set_snr_db,
             py::arg("snr_db"),
             "Change the SNR at the initial distance from now on (dB).")
        .def("set_heading_noise_rad",
             &world::set_heading_noise_rad,
             py::arg("sigma"),
             "Change the heading sensor's noise std from now on (rad).")
        .def("set_turn_rate_rad_per_s",
             &world::set_turn_rate_rad_per_s,
             py::arg("rate"),
             "Change the turn-rate limit from now on (rad/s; 0: instantaneous).")
        .def_static(
            "wrap", &world::wrap, py::arg("angle"), "Wrap an angle to (-pi, pi].");
}

} // namespace

namespace {

// The scene: scatterers and the paths at the UAV.
void bind_scene_classes(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<scatterer>(m, "scatterer", "Point scatterer: position and Gamma_i.")
        .def_readonly("x_m", &scatterer::x_m, "East position (m).")
        .def_readonly("y_m", &scatterer::y_m, "North position (m).")
        .def_readonly("gamma", &scatterer::gamma, "Reflection coefficient.");
    py::class_<path_state>(m, "path_state", "One path at the UAV (LOS first).")
        .def_readonly("amplitude",
                      &path_state::amplitude,
                      "complex amplitude of the received path (sqrt W)")
        .def_readonly("doppler_hz",
                      &path_state::doppler_hz,
                      "+f_d,max cos(heading - direction to source point)")
        .def_readonly("length_m", &path_state::length_m, "emitter -> (scatterer ->) UAV");
}

// The wind and the velocity over the ground.
void bind_world_wind(py::class_<gr::rfseek::world>& w)
{
    using namespace gr::rfseek;
    w.def_property_readonly("wind_east_mps",
                            &world::wind_east_mps,
                            "The mean wind now (without gusts), m/s.");
    w.def_property_readonly("wind_north_mps",
                            &world::wind_north_mps,
                            "The mean wind now, north component (m/s, without gusts).");
    w.def_property_readonly("start_wind_to_rad",
                            &world::start_wind_to_rad,
                            "Where the mean wind blew toward at the start (rad; "
                            "drawn from the seed when not given, even at 0 m/s).");
    w.def_property_readonly("ground_vx_mps",
                            &world::ground_vx_mps,
                            "Velocity over the ground (air velocity + wind), m/s.");
    w.def_property_readonly("ground_vy_mps",
                            &world::ground_vy_mps,
                            "Velocity over the ground, north component (m/s).");
}

// Following a vehicle flown by something else (SITL).
void bind_world_follow(py::module& m, py::class_<gr::rfseek::world>& w)
{
    using namespace gr::rfseek;
    py::class_<vehicle_truth>(
        m,
        "vehicle_truth",
        "One true state of a vehicle flown by a flight simulator: time_s (its clock), "
        "east_m, north_m, up_m (a local level frame whose height is the emitter's "
        "ground), v_east_mps, v_north_mps, v_up_mps (over the ground), heading_rad "
        "(true, counter-clockwise from east).")
        .def(py::init<>(), "A state at rest at the frame's origin, time 0.")
        .def_readwrite(
            "time_s", &vehicle_truth::time_s, "Time on the simulator's clock (s).")
        .def_readwrite(
            "east_m", &vehicle_truth::east_m, "East of the frame's origin (m).")
        .def_readwrite(
            "north_m", &vehicle_truth::north_m, "North of the frame's origin (m).")
        .def_readwrite("up_m", &vehicle_truth::up_m, "Above the emitter's ground (m).")
        .def_readwrite("v_east_mps",
                       &vehicle_truth::v_east_mps,
                       "Velocity over the ground, east (m/s).")
        .def_readwrite("v_north_mps",
                       &vehicle_truth::v_north_mps,
                       "Velocity over the ground, north (m/s).")
        .def_readwrite(
            "v_up_mps", &vehicle_truth::v_up_mps, "Vertical velocity, up (m/s).")
        .def_readwrite("heading_rad",
                       &vehicle_truth::heading_rad,
                       "True heading (rad, counter-clockwise from east).");
    w.def("follow",
          &world::follow,
          py::arg("truth"),
          "This slot's state is the truth (a vehicle flown by SITL): the first call "
          "places the emitter (the vehicle where the scenario starts it, the scene "
          "turned about the emitter so that the truth's heading sees it as the "
          "scenario's start heading does), each later one is the next slot. ValueError "
          "for a non-finite field or a time before the "
          "last; RuntimeError once finished.");
    w.def_property_readonly("following", &world::following, "follow() has been called.");
    w.def_property_readonly(
        "altitude_m", &world::altitude_m, "Height above the emitter's ground (m).");
    w.def_property_readonly(
        "up_mps", &world::up_mps, "Vertical speed (m/s, up); 0 unless following.");
}

} // namespace

void bind_world(py::module& m)
{
    using namespace gr::rfseek;
    bind_scene_classes(m);
    auto w =
        py::class_<world>(
            m, "world", "The simulated physics of one run, slot by slot (paper eq. 1-2).")
            .def(py::init<const scenario&>(),
                 py::arg("scenario"),
                 "Validates the scenario and draws the geometry, start and CFO from its "
                 "seed.")
            .def_property_readonly("config", &world::config, "The scenario it simulates.")
            .def_property_readonly(
                "scatterers",
                &world::scatterers,
                "The scatterers' positions and reflection coefficients.")
            .def_property_readonly(
                "slot", &world::slot, "Current slot index (state at its start).")
            .def_property_readonly(
                "time_s", &world::time_s, "Time at the start of the current slot (s).")
            .def_property_readonly(
                "x_m", &world::x_m, "UAV east position (m; emitter at the origin).")
            .def_property_readonly(
                "y_m", &world::y_m, "UAV north position (m; emitter at the origin).")
            .def_property_readonly("heading_rad",
                                   &world::heading_rad,
                                   "True air heading flown (rad, CCW from east).")
            .def_property_readonly("bank_rad",
                                   &world::bank_rad,
                                   "Bank angle (rad, + turning counter-clockwise); 0 "
                                   "unless the turns are coordinated.")
            .def_property_readonly("measured_heading_rad",
                                   &world::measured_heading_rad,
                                   "Heading the UAV's sensors report for this slot: the "
                                   "true heading minus the "
                                   "compass error it flies with, plus sigma_phi noise.")
            .def_property_readonly(
                "distance_m",
                &world::distance_m,
                "Horizontal distance to the emitter (what d_v is judged on).")
            .def_property_readonly(
                "distance_flown_m",
                &world::distance_flown_m,
                "Distance flown through the air (what the battery pays).")
            .def_property_readonly("straight_air_m",
                                   &world::straight_air_m,
                                   "What the straight ground line costs: the air "
                                   "distance a vehicle pays flying the straight ground "
                                   "track from the start to d_v, crabbed into the mean "
                                   "wind at the start (d - d_v in calm air; infinity "
                                   "when that wind blows it back).")
            .def_property_readonly(
                "flight_cap_m",
                &world::flight_cap_m,
                "Air distance at which the run is capped: flight_cap_m, or 4 x "
                "straight_air_m where that is longer than d - d_v (a headwind), else "
                "4 (d - d_v).")
            .def_property_readonly("bearing_to_emitter_rad",
                                   &world::bearing_to_emitter_rad,
                                   "Bearing from the UAV toward the emitter.")
            .def_property_readonly("cfo_hz",
                                   &world::cfo_hz,
                                   "Carrier offset f_o at the start of this slot, and "
                                   "its linear drift rate a.")
            .def_property_readonly("cfo_drift_hz_per_s",
                                   &world::cfo_drift_hz_per_s,
                                   "The carrier offset's linear drift rate (Hz/s).")
            .def_property_readonly(
                "los_doppler_hz",
                &world::los_doppler_hz,
                "Doppler of the line-of-sight path (+ when approaching).")
            .def_property_readonly(
                "slant_range_m",
                &world::slant_range_m,
                "Straight-line (3-D) distance to the emitter, altitude included.")
            .def_property_readonly(
                "compass_error_rad",
                &world::compass_error_rad,
                "Compass error of the heading flown in this slot (flown - commanded).")
            .def_property_readonly(
                "amplitude_scale",
                &world::amplitude_scale,
                "Signal amplitude scale A (sqrt W * m) set from snr_db at "
                "the initial distance.")
            .def_property_readonly(
                "noise_power", &world::noise_power, "Noise power per sample (W).")
            .def_property_readonly("arrived",
                                   &world::arrived,
                                   "Within d_v of the emitter (horizontal). Ends the run "
                                   "unless self_arrival.")
            .def_property_readonly(
                "capped", &world::capped, "The flight cap was reached (ends the run).")
            .def_property_readonly(
                "reached",
                &world::reached,
                "Has been within d_v at some slot (the same as arrived() "
                "without self_arrival).")
            .def_property_readonly(
                "reached_flown_m",
                &world::reached_flown_m,
                "Distance flown when d_v was first reached (0 if not reached).")
            .def_property_readonly(
                "ended",
                &world::ended,
                "self_arrival: the vehicle declared the run over (end_run()).");
    bind_world_wind(w);
    bind_world_methods(w);
    bind_world_follow(m, w);
}
