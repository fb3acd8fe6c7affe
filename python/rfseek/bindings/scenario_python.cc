/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(scenario.h) */
/* BINDTOOL_HEADER_FILE_HASH(6a40c04fd3a6ba37c559e7b6f42f9bae) */

#include "kwargs.h"
#include <gr-rfseek/scenario.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <algorithm>

namespace py = pybind11;

namespace {

// The scenario's methods (its fields are bound in bind_scenario).
void bind_scenario_methods(py::class_<gr::rfseek::scenario>& c)
{
    using gr::rfseek::scenario;
    c.def("validate", &scenario::validate, "Raise ValueError naming a bad field.")
        .def_property_readonly(
            "wavelength_m", &scenario::wavelength_m, "lambda = c / carrier_hz (m).")
        .def_property_readonly("max_doppler_hz",
                               &scenario::max_doppler_hz,
                               "f_d,max = speed_mps * carrier_hz / c (Hz).")
        .def_property_readonly(
            "slot_samples", &scenario::slot_samples, "round(T_slot * fs)")
        .def_property_readonly("window_duration_s",
                               &scenario::window_duration_s,
                               "window_len / samp_rate_hz (s).")
        .def_property_readonly(
            "shortest_path_m",
            &scenario::shortest_path_m,
            "initial_distance_m - success_radius_m: the straight line to d_v (m).")
        .def_property_readonly(
            "effective_flight_cap_m",
            &scenario::effective_flight_cap_m,
            "The flight cap in calm air, metres (flight_cap_m, default 4 (d - d_v)); "
            "world.flight_cap_m is the one flown (into a headwind the default is 4 x "
            "the straight line's air distance).")
        .def_static("keys",
                    &scenario::keys,
                    "Names of the numeric fields settable by set() (CLI \"--set "
                    "key=value\", GRC).")
        .def("set",
             &scenario::set,
             py::arg("key"),
             py::arg("value"),
             "Set a field by name from text: numbers, \"true\"/\"false\" for add_noise, "
             "\"none\"/\"random\" to unset an optional field. Throws "
             "ValueError for an unknown key or unparsable value (validate() "
             "checks ranges).")
        .def("get",
             &scenario::get,
             py::arg("key"),
             "Field value as text (\"none\" for an unset optional).")
        .def("to_json", &scenario::to_json, "All fields as a JSON object (one line).")
        .def_static("presets", &scenario::presets, "Names of the study presets.")
        .def_static("preset_overrides",
                    &scenario::preset_overrides,
                    py::arg("name"),
                    "A preset's (key, value) overrides of the reference scenario.")
        .def_static("preset_description",
                    &scenario::preset_description,
                    py::arg("name"),
                    "One line saying what the preset is.")
        .def_static(
            "preset",
            [](const std::string& name) {
                scenario s;
                s.apply_preset(name);
                return s;
            },
            py::arg("name"),
            "The reference scenario with a preset applied.")
        .def("apply_preset",
             &scenario::apply_preset,
             py::arg("name"),
             "Apply a preset's overrides to this scenario (throws for an unknown name).")
        .def(
            "copy", [](const scenario& s) { return scenario(s); }, "An independent copy.")
        .def("__repr__",
             [](const scenario& s) { return "rfseek.scenario(" + s.to_json() + ")"; });
}

} // namespace

void bind_scenario(py::module& m)
{
    using gr::rfseek::scenario;
    m.attr("SPEED_OF_LIGHT") = gr::rfseek::SPEED_OF_LIGHT;

    py::class_<scenario> c(
        m,
        "scenario",
        "All parameters of a simulated run. Defaults: the reference "
        "scenario (paper Table I + docs/design.md). Fields set to None are "
        "drawn from the seed. scenario(**fields) sets fields by name.");
    c.def(py::init([](const py::kwargs& kw) {
              scenario v = rfseek_from_kwargs<scenario>(kw, "scenario");
              if (!kw.empty())
                  v.validate(); // the object made (defaults elsewhere): ValueError naming
                                // a field
              return v;
          }),
          "A scenario with the reference defaults; keyword arguments set fields by name "
          "(TypeError for an unknown one). The scenario made is then validated, the "
          "other fields at their defaults: ValueError naming a field out of range. To "
          "build one in steps, make scenario() and set attributes; blocks and "
          "validate() check it.");
#define RW(NAME, DOC) c.def_readwrite(#NAME, &scenario::NAME, DOC)
    RW(initial_distance_m, "d: UAV to emitter at start (m)");
    RW(start_angle_rad, "alpha: UAV polar angle around the emitter (None: from seed)");
    RW(start_heading_rad, "initial heading (None: from seed)");
    RW(num_scatterers, "L: scatterer count");
    RW(scatterer_inner_radius_m, "R_in (m)");
    RW(scatterer_outer_radius_m, "R (m)");
    RW(gamma_min, "lower bound of |Gamma_i|");
    RW(gamma_max, "upper bound of |Gamma_i|");
    RW(carrier_hz, "f_c (Hz)");
    RW(samp_rate_hz, "1/Ts (Hz)");
    RW(window_len, "N: beacon samples");
    RW(slot_period_s, "T_slot (s)");
    RW(fft_len, "N_FFT");
    RW(snr_db, "mean per-sample SNR at the initial distance (dB)");
    RW(noise_power_db, "sigma_n^2 (dB)");
    RW(add_noise, "False: noise-free samples");
    RW(cfo_hz, "initial CFO f_o(0) (None: uniform in +-cfo_range_hz)");
    RW(cfo_range_hz, "range of the random initial CFO (Hz)");
    RW(cfo_drift_hz_per_s, "linear CFO drift a (None: uniform in +-range)");
    RW(cfo_drift_range_hz_per_s, "range of the random drift (Hz/s)");
    RW(cfo_walk_hz_per_sqrt_s, "CFO random-walk strength (Hz/sqrt(s))");
    RW(speed_mps, "v (m/s)");
    RW(heading_noise_rad, "sigma_phi: heading measurement noise (rad)");
    RW(turn_rate_rad_per_s, "maximum turn rate (rad/s); 0 = instantaneous");
    RW(bank_limit_rad,
       "bank limit of coordinated turns (rad, <= 80 deg; turn rate g tan(bank) / v); 0 = "
       "none");
    RW(roll_rate_rad_per_s,
       "roll-rate limit with bank_limit_rad (rad/s, <= 20); 0 = instantaneous roll");
    RW(altitude_m, "UAV height above the emitter (m); scatterers on the ground");
    RW(wind_speed_mps, "mean wind speed (m/s)");
    RW(wind_to_rad,
       "direction the wind blows toward (rad, CCW from east; None: from seed)");
    RW(wind_gust_mps, "gust standard deviation per axis (m/s), first-order Gauss-Markov");
    RW(wind_gust_tau_s, "gust correlation time (s)");
    RW(compass_bias_rad, "compass bias: flown heading = commanded + bias + noise (rad)");
    RW(compass_noise_rad, "compass noise on the flown heading, white per slot (rad)");
    RW(wind_veer_rad_per_s, "the mean wind's direction turns at this rate (rad/s, CCW)");
    RW(airspeed_error_mps,
       "airspeed the vehicle believes minus the one it flies (m/s; seeker_for adds it)");
    RW(altimeter_error_m,
       "altitude the vehicle believes minus the true one (m; seeker_for adds it)");
    RW(wind_forecast,
       "hand the seeker a wind forecast: the run's mean wind at the start, off by the "
       "two errors below");
    RW(wind_forecast_speed_error_mps, "forecast wind speed - true (m/s)");
    RW(wind_forecast_direction_error_rad, "forecast wind direction - true (rad)");
    RW(success_radius_m, "d_v (m)");
    RW(flight_cap_m,
       "flight cap, air metres; None = 4 x the straight ground line's air distance, "
       "at least 4 (d - d_v)");
    RW(self_arrival,
       "the run ends on the vehicle's own declaration (seeker_config.self_arrival); d_v "
       "stays a metric");
    RW(seed, "seed of every random draw of the run");
#undef RW
    bind_scenario_methods(c);
}
