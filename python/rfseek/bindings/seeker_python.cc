/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(seeker.h) */
/* BINDTOOL_HEADER_FILE_HASH(a2ae14c95fd587031290175f5c6b3369) */

#include "kwargs.h"
#include <gr-rfseek/seeker.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <algorithm>

namespace py = pybind11;

namespace {

// The fields of arrival without truth and of the emitter locator.
void bind_arrival_fields(py::class_<gr::rfseek::seeker_config>& c)
{
    using gr::rfseek::seeker_config;
#define RW(NAME, DOC) c.def_readwrite(#NAME, &seeker_config::NAME, DOC)
    RW(self_arrival,
       "detect the overflight, loiter and locate the emitter (any strategy); False: the "
       "strategy only");
    RW(arrival_swing, "overflight: frequency drop beyond turns and drift, x f_d,max");
    RW(arrival_window_s, "overflight: the drop must happen within this time (s)");
    RW(arrival_heading_band_rad,
       "overflight: heading spread allowed over the drop (rad)");
    RW(arrival_power_rise_db, "overflight: power peak above the drop's lower end (dB)");
    RW(arrival_near_swing,
       "overflight near the emitter (power arrival_near_power_db above the start's): "
       "this drop x f_d,max suffices (0: off; else in [0.5, arrival_swing])");
    RW(arrival_near_power_db,
       "overflight: the power rise over the beacon's power at the start (dB) from which "
       "arrival_near_swing applies");
    RW(arrival_block_slots, "overflight: slots per median block");
    RW(arrival_confirm_blocks, "overflight: consecutive blocks with the signature");
    RW(arrival_encircle,
       "encircling: headings all round over 120 s with the far-field Doppler amplitude "
       "below this x f_d,max (0: off)");
    RW(arrival_far_amplitude,
       "a loiter whose first orbit shows a Doppler amplitude of at least this x "
       "f_d,max is a false overflight: seek on at once (0: off; see far_amplitude)");
    RW(arrival_confirm_m,
       "arrival is declared when a location fit falls within this distance of the "
       "estimate orbited, by the vehicle, and (locate_nuisance) its honest 95 % "
       "semi-major axis is at most 600 m (m; 0: on the overflight alone). A loiter held "
       "back by that rule arrives when the orbits allowed run out if, with "
       "locate_altitude_m >= 50 m, its last two orbits around the estimate swing the "
       "Doppler by less than 2/3 of far_amplitude(), as over the emitter; its fix is "
       "then published unsure. So does a loiter none of whose fits agree (in gusts), "
       "if the last lay within 4 x this of the estimate: a fit of all the data, within "
       "600 m, is published unsure.");
    RW(loiter_radius_m, "loiter orbit radius (m), flown to the left");
    RW(loiter_heading_gain,
       "gain in (0, 1] of the alpha-beta filter that smooths the heading read for the "
       "loiter's dead reckoning and location fits (1: the read itself)");
    RW(locate_orbits, "orbits of data before the first location fit");
    RW(locate_max_orbits,
       "no fix after this many orbits (extended by each move of the estimate and by the "
       "arrival): seek again or give up");
    RW(locate_retry, "seek again after locate_max_orbits without a fix (else done)");
    RW(locate_max_axis_m,
       "publish a fix when its 95 % ellipse semi-major axis is below (m)");
    RW(locate_gust_mps,
       "location fit: gust prior, std per axis (m/s; 0: a constant wind only)");
    RW(locate_gust_tau_s, "location fit: gust correlation time (s)");
    RW(locate_split_gate,
       "the fix's split check: where the disagreement T of its data's halves exceeds "
       "this (chi-square, 2 dof; 5.99: the 95 % point), the ellipse grows by "
       "sqrt(T / 2); 0: off");
    RW(locate_nuisance,
       "the fix carries what the flight does not know: refitted under wide gust models "
       "and altimeter readings off by +- locate_altimeter_range_m, its ellipse theirs "
       "mixed by evidence and calibrated (False: the prior's fit alone)");
    RW(locate_altimeter_range_m, "altimeter error the fix carries (m, 0..1000)");
    RW(locate_scale95,
       "the user's factor on the honest 95 % ellipse's radii, on top of the calibrated "
       "ones (0.1..10; above 1 for a day rougher than the calibration's envelope); the "
       "wider ellipse also decides sure or unsure");
    RW(locate_scale50, "the same for the 50 % ellipse (0.1..10)");
    RW(locate_altitude_m,
       "location fit: the vehicle's height above the emitter's ground as its altimeter "
       "holds it (m; NaN: unknown, no height prior)");
    RW(locate_altitude_sigma_m,
       "location fit: std of the height prior, the altimeter's stated accuracy (m; 0: "
       "the height is fitted freely); fits more than 2.5 x this above "
       "locate_altitude_m, or below both that band and twice the height at which an "
       "orbit centred on the emitter swings as far as far_amplitude, are not used");
#undef RW
}

void bind_seeker_config(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<seeker_config> c(m,
                                "seeker_config",
                                "Strategy and constants of the seeker. "
                                "seeker_config(**fields) sets fields by name.");
    c.def(py::init([](const py::kwargs& kw) {
              seeker_config v = rfseek_from_kwargs<seeker_config>(kw, "seeker_config");
              if (!kw.empty())
                  v.validate(); // the object made (defaults elsewhere): ValueError naming
                                // a field
              return v;
          }),
          "A configuration with the paper's constants; keyword arguments set fields by "
          "name (TypeError for an unknown one). The configuration made is then "
          "validated, the other fields at their defaults: ValueError naming a field out "
          "of range. To build one in steps, make seeker_config() and set attributes.");
#define RW(NAME, DOC) c.def_readwrite(#NAME, &seeker_config::NAME, DOC)
    RW(strategy,
       "'paper', 'paper_no_circle', 'rss_baseline' or 'adaptive' (ours, not the "
       "paper's)");
    RW(speed_mps, "v (m/s)");
    RW(carrier_hz, "f_c (Hz)");
    RW(slot_period_s, "T_slot (s)");
    RW(delta_rad, "Stage-2 perturbation delta (rad)");
    RW(delta_max_rad, "paper: largest Stage-2 delta_k (rad; <= delta_rad: delta fixed)");
    RW(delta_step_rad, "paper: most delta_k grows per Stage-2 step (rad)");
    RW(delta_after_steps,
       "paper: steps in a row measuring an error beyond delta, on one side, before "
       "delta_k grows");
    RW(m_slots, "M: slots per half step");
    RW(circle_radius_m, "R_c of the Stage-1 circle (m)");
    RW(moving_average_len, "Stage-1 moving average (slots)");
    RW(outlier_threshold_hz, "eq. 4 threshold (Hz); 0 = 2 f_d,max");
    RW(literal_eq4, "eq. 4 as printed (compare with the previous raw value)");
    RW(relock_count, "re-lock after this many agreeing rejections");
    RW(lock_count, "eq. 4 locks once this many consecutive candidates agree");
    RW(min_snr_db,
       "values whose estimated SNR is below this are no eq. 4 candidates (dB)");
    RW(stage1_fit,
       "paper: Stage 1 by least squares with a CFO trend (False: the paper's argmax)");
    RW(turn_rate_rad_per_s, "vehicle turn-rate limit (rad/s); 0 = instantaneous");
    RW(bank_limit_rad, "vehicle bank limit (rad, <= 80 deg); 0 = none");
    RW(roll_rate_rad_per_s,
       "vehicle roll-rate limit with bank_limit_rad (rad/s, <= 20); 0 = instantaneous");
    RW(hold_after_missing, "slots without valid measurements before holding course");
    RW(initial_heading_rad,
       "Stage-2 start for paper_no_circle (None: first measured heading)");
    RW(seed, "seed (circle turning sense, RSS tumbles)");
    RW(rss_block_m, "rss_baseline: length over which a run's power is averaged (m)");
    RW(rss_window_blocks,
       "rss_baseline: blocks per long-term average (a run ends when the last window's "
       "mean falls below the window before)");
    RW(rss_fall_db, "rss_baseline: fall of the long-term average that ends a run (dB)");
    RW(adaptive_acquire_slots, "adaptive: slots per acquisition heading");
    RW(adaptive_relocate_slots,
       "adaptive: slots flown straight on before an acquisition is retried");
    RW(adaptive_track_slots, "adaptive: slots per probe segment (4 per cycle)");
    RW(adaptive_turn_share,
       "adaptive, any turn limit: the largest share of a probe cycle spent reversing "
       "(in (0, 1])");
    RW(adaptive_gain, "adaptive: fraction of the measured error removed per cycle");
    RW(adaptive_delta_min_rad, "adaptive: smallest probe half-angle (rad)");
    RW(adaptive_delta_max_rad, "adaptive: largest probe half-angle (rad)");
    RW(adaptive_reacquire_rad,
       "adaptive: errors beyond this start a new acquisition (rad)");
    RW(adaptive_drift, "adaptive: fit a linear CFO drift per probe cycle");
    RW(adaptive_scatter_delta,
       "adaptive: size delta for the bearing scatter of the cycles when larger than the "
       "fit's white-noise figure (gusts)");
    RW(adaptive_ground_track,
       "adaptive: crab into the wind until the bearing stops turning (a straight ground "
       "track)");
    RW(ground_track_gain,
       "adaptive's ground track: crab change per bearing change (proportional "
       "navigation N - 1)");
    RW(ground_track_max_crab_rad, "ground track: |crab| limit (rad)");
    RW(ground_track_gate,
       "ground track: the crab moves while the bearing rate exceeds this many std");
    RW(ground_track_rate_walk,
       "ground track: random walk of the bearing rate in its filter (rad/s/sqrt(s))");
    RW(wind_forecast_east_mps,
       "ground track: wind forecast toward east (m/s, compass frame; both 0: no "
       "forecast)");
    RW(wind_forecast_north_mps,
       "ground track: wind forecast toward north (m/s, compass frame; both 0: no "
       "forecast)");
    RW(paper_ground_track,
       "paper, paper_no_circle: fly Stage 2's probes around theta plus the ground-track "
       "crab (off: the paper's air heading at theta)");
    RW(paper_ground_track_gain,
       "paper_ground_track: crab change per bearing change (proportional navigation "
       "N - 1)");
    bind_arrival_fields(c);
#undef RW
    c.def("validate",
          &seeker_config::validate,
          "Raise ValueError naming the first field out of its allowed range.")
        .def_static(
            "keys",
            &seeker_config::keys,
            "Every key set() accepts (fields, and *_deg aliases of the *_rad ones).")
        .def("set",
             &seeker_config::set,
             py::arg("key"),
             py::arg("value"),
             "Set a field from text (as --set KEY=VALUE does): numbers, true/false, "
             "degrees for *_deg keys, 'none' for initial_heading_rad. ValueError for an "
             "unknown key or an unparsable value; ranges are checked by validate().")
        .def_property_readonly("max_doppler_hz",
                               &seeker_config::max_doppler_hz,
                               "f_d,max = speed_mps * carrier_hz / c (Hz).")
        .def_property_readonly("effective_outlier_threshold_hz",
                               &seeker_config::effective_outlier_threshold_hz,
                               "outlier_threshold_hz, or 2 f_d,max when it is 0.")
        .def_property_readonly("far_amplitude",
                               &seeker_config::far_amplitude,
                               "Swing (x f_d,max) of a first orbit far away.");
}

} // namespace

void bind_seeker(py::module& m)
{
    using namespace gr::rfseek;
    bind_seeker_config(m);

    py::class_<measurement>(
        m, "measurement", "One slot's measurement as the seeker sees it.")
        .def(py::init<>(), "An empty measurement.")
        .def_readwrite("slot", &measurement::slot, "Slot index.")
        .def_readwrite("time_s", &measurement::time_s, "Time of the slot (s).")
        .def_readwrite("freq_hz",
                       &measurement::freq_hz,
                       "Measured frequency (Hz): Doppler plus carrier offset.")
        .def_readwrite("snr_db", &measurement::snr_db, "Estimated SNR (dB).")
        .def_readwrite("power_db", &measurement::power_db, "Estimated tone power (dB).")
        .def_readwrite("valid", &measurement::valid, "The estimate is usable.")
        .def_readwrite("has_heading",
                       &measurement::has_heading,
                       "heading_rad holds the vehicle's heading for this slot.")
        .def_readwrite(
            "heading_rad", &measurement::heading_rad, "measured heading at the beacon");

    py::class_<command>(m, "command", "The seeker's answer to one measurement.")
        .def(py::init<>(), "An empty command.")
        .def_readonly("slot", &command::slot, "slot of the measurement answered")
        .def_readonly("heading_rad", &command::heading_rad, "heading to fly from now on")
        .def_readonly("stage",
                      &command::stage,
                      "1 (circle, acquisition), 2 (perturbations, probes), 3 (loiter)")
        .def_readonly("theta_est_rad",
                      &command::theta_est_rad,
                      "current estimate of the direction to the emitter")
        .def_readonly("update",
                      &command::update,
                      "a Stage-2 update (eq. 5) or the Stage-1 decision happened")
        .def_readonly(
            "holding", &command::holding, "holding course for lack of measurements")
        .def_readonly("filtered_freq_hz",
                      &command::filtered_freq_hz,
                      "the eq. 4 output for this measurement")
        .def_readonly("accepted", &command::accepted, "eq. 4 accepted this measurement")
        .def_readonly("status", &command::status, "0 seeking, 1 arrived, 2 located")
        .def_readonly("done",
                      &command::done,
                      "self_arrival: the mission is over (located, or gave up after "
                      "locate_max_orbits).")
        .def_readonly(
            "location", &command::location, "the latest fix (valid once located)");

    py::class_<seeker, std::unique_ptr<seeker>>(m, "seeker", "A seeking strategy.")
        .def(py::init(&seeker::make),
             py::arg("config"),
             "The strategy config.strategy with config's constants (validated).")
        .def_static("make",
                    &seeker::make,
                    py::arg("config"),
                    "The strategy config.strategy with config's constants (validated).")
        .def_static("strategies", &seeker::strategies, "The strategy names.")
        .def("update",
             &seeker::update,
             py::arg("measurement"),
             "Take one slot's measurement; return the command (heading to fly, stage, "
             "status).")
        .def("config", &seeker::config, "The seeker_config it runs with.")
        .def("stage",
             &seeker::stage,
             "1 circle or acquisition, 2 perturbations or probes, 3 loiter (arrival).")
        .def("theta_est_rad",
             &seeker::theta_est_rad,
             "The current estimate of the emitter's bearing (rad).")
        .def("updates", &seeker::updates, "Heading updates applied so far.")
        .def(
            "set_wind_forecast",
            [](seeker& s, double east_mps, double north_mps) {
                seeker_config c = s.config(); // checked as the controller checks it
                c.wind_forecast_east_mps = east_mps;
                c.wind_forecast_north_mps = north_mps;
                c.validate();
                return s.set_wind_forecast(east_mps, north_mps);
            },
            py::arg("east_mps"),
            py::arg("north_mps"),
            "A new wind forecast for the ground track, mid-flight (m/s toward east and "
            "north; both 0: none); it replaces what the law had learned. False (nothing "
            "changed) for a strategy without a ground track; ValueError for bad values.");
}
