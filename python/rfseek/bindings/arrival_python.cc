/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(arrival.h) */
/* BINDTOOL_HEADER_FILE_HASH(38b8743aa8ccba4d52310848100bf7d7) */

#include <gr-rfseek/arrival.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <cstdio>
#include <limits>
#include <string>

namespace py = pybind11;

namespace {

void bind_overflight_config_class(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<overflight_config>(m, "overflight_config", "Overflight detector settings.")
        .def(py::init<>(),
             "The detector's constants (defaults: docs/seeker.md); keyword arguments set "
             "them.")
        .def_readwrite("max_doppler_hz",
                       &overflight_config::max_doppler_hz,
                       "f_d,max = v f_c / c (airspeed)")
        .def_readwrite(
            "slot_period_s", &overflight_config::slot_period_s, "Slot period (s).")
        .def_readwrite(
            "swing",
            &overflight_config::swing,
            "Required frequency drop beyond what the heading change explains, x f_d,max.")
        .def_readwrite("window_s",
                       &overflight_config::window_s,
                       "the drop must happen within this time")
        .def_readwrite("heading_band_rad",
                       &overflight_config::heading_band_rad,
                       "heading spread allowed over the drop (60 deg)")
        .def_readwrite("power_rise_db",
                       &overflight_config::power_rise_db,
                       "peak power over the drop above its lower end")
        .def_readwrite("drift_s",
                       &overflight_config::drift_s,
                       "The CFO drift is fitted over this much flight before each block "
                       "(any headings).")
        .def_readwrite("block_slots",
                       &overflight_config::block_slots,
                       "slots per median block (2 s at 50 ms)")
        .def_readwrite("confirm_blocks",
                       &overflight_config::confirm_blocks,
                       "consecutive blocks the signature must hold")
        .def_readwrite("min_snr_db",
                       &overflight_config::min_snr_db,
                       "measurements below are not used")
        .def_readwrite(
            "encircle_amplitude",
            &overflight_config::encircle_amplitude,
            "Encircling: detected also when, over drift_s with headings all round, the "
            "far-field Doppler amplitude stays below this x f_d,max (0: off).")
        .def_readwrite("near_swing",
                       &overflight_config::near_swing,
                       "Near the emitter a smaller drop suffices: near_swing x f_d,max "
                       "(in [0.5, swing]; 0: off) once the power over the drop has risen "
                       "near_power_db above the beacon's power at the start.")
        .def_readwrite("near_power_db",
                       &overflight_config::near_power_db,
                       "dB above the start's power (0..100)");
}

void bind_doppler_amplitude_class(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<doppler_amplitude>(
        m,
        "doppler_amplitude",
        "The Doppler amplitude of a turn: hypot(p, q) of c + d t + p cos(psi) + q "
        "sin(psi) fitted robustly; f_d,max far from the emitter, much less near it.")
        .def(py::init<>(), "An empty amplitude fit.")
        .def("add",
             &doppler_amplitude::add,
             py::arg("time_s"),
             py::arg("heading_rad"),
             py::arg("freq_hz"),
             "Add one measurement: time (s), heading (rad), frequency (Hz); non-finite "
             "ones are skipped.")
        .def("clear",
             &doppler_amplitude::clear,
             "One measurement (non-finite ones are skipped; at most 20000 are kept).")
        .def("__len__", &doppler_amplitude::size)
        .def_property_readonly(
            "amplitude",
            &doppler_amplitude::amplitude,
            "The fitted amplitude (Hz); NaN with fewer than 8 measurements or headings "
            "that do not go all round (a gap of 120 deg or more).");
}

void bind_overflight_detector_class(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<overflight_detector>(
        m,
        "overflight_detector",
        "The overflight signature: the Doppler swings toward -f_d,max at a steady "
        "heading while the power peaks; or the encircling one: headings all round, the "
        "far-field Doppler amplitude collapsed.")
        .def(py::init<const overflight_config&>(),
             py::arg("config") = overflight_config(),
             "A detector with these constants (validated).")
        .def("update",
             &overflight_detector::update,
             py::arg("time_s"),
             py::arg("freq_hz"),
             py::arg("power_db"),
             py::arg("snr_db"),
             py::arg("valid"),
             py::arg("heading_rad"),
             "One slot. heading_rad: the measured heading. Returns true once detected "
             "(and from then on).")
        .def_property_readonly("detected",
                               &overflight_detector::detected,
                               "The overflight (or encircling) signature was seen.")
        .def_property_readonly("detect_time_s",
                               &overflight_detector::detect_time_s,
                               "Time of the slot that completed the detection.")
        .def_property_readonly("last_drop_hz",
                               &overflight_detector::last_drop_hz,
                               "The largest heading-corrected drop seen in the last "
                               "block (diagnostics, Hz).")
        .def_property_readonly("last_amplitude_hz",
                               &overflight_detector::last_amplitude_hz,
                               "The far-field Doppler amplitude fitted at the last block "
                               "(Hz; NaN while the headings do not go all round).")
        .def_property_readonly(
            "encircled",
            &overflight_detector::encircled,
            "The detection came from the encircling signature, not an overflight.")
        .def_property_readonly(
            "start_power_db",
            &overflight_detector::start_power_db,
            "The beacon's power when the detector was made: the median "
            "of its first START_BLOCKS usable blocks (dB; NaN until "
            "then). reset() keeps it.")
        .def("reset",
             &overflight_detector::reset,
             "Forget the approach (a new one); the start's power is kept.");
}

void bind_emitter_location_class(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<emitter_location>(
        m, "emitter_location", "A location fix (docs/seeker.md).")
        .def(py::init<>(), "An empty location (invalid).")
        .def_readonly(
            "valid", &emitter_location::valid, "A fix was made (every field finite).")
        .def_readonly("time_s", &emitter_location::time_s, "time of the fix")
        .def_readonly("east_m",
                      &emitter_location::east_m,
                      "emitter relative to the vehicle at time_s")
        .def_readonly(
            "north_m", &emitter_location::north_m, "(x east, y north, compass frame)")
        .def_readonly("dr_x_m",
                      &emitter_location::dr_x_m,
                      "vehicle in the dead-reckoned frame (origin:")
        .def_readonly("dr_y_m", &emitter_location::dr_y_m, "where the loiter began)")
        .def_readonly("major_m",
                      &emitter_location::major_m,
                      "95 % uncertainty ellipse: semi-major axis")
        .def_readonly("minor_m", &emitter_location::minor_m, "semi-minor axis")
        .def_readonly("major_angle_rad",
                      &emitter_location::major_angle_rad,
                      "direction of the major axis (CCW from east)")
        .def_readonly("wind_east_mps",
                      &emitter_location::wind_east_mps,
                      "estimated wind (nuisance)")
        .def_readonly("wind_north_mps",
                      &emitter_location::wind_north_mps,
                      "The fit's mean wind, north component (m/s).")
        .def_readonly("wind_sigma_mps",
                      &emitter_location::wind_sigma_mps,
                      "standard error of each wind component")
        .def_readonly("altitude_m",
                      &emitter_location::altitude_m,
                      "estimated height above the emitter (nuisance)")
        .def_readonly("cfo_hz", &emitter_location::cfo_hz, "estimated CFO at time_s")
        .def_readonly(
            "rms_hz", &emitter_location::rms_hz, "residual RMS of the fit's inliers")
        .def_readonly(
            "used", &emitter_location::used, "measurements in the fit (inliers)")
        .def_readonly("inflation",
                      &emitter_location::inflation,
                      "covariance inflation for correlated residuals")
        .def_readonly("gust_knots",
                      &emitter_location::gust_knots,
                      "gust states per axis (0: constant wind)")
        .def_readonly("consistency",
                      &emitter_location::consistency,
                      "the split check's T: the disagreement of the data's halves, "
                      "chi-square with 2 degrees of freedom for a right ellipse (-1: "
                      "not run)")
        .def_readonly("major50_m",
                      &emitter_location::major50_m,
                      "50 % uncertainty ellipse: semi-major axis")
        .def_readonly("minor50_m", &emitter_location::minor50_m, "semi-minor axis")
        .def_readonly("hypotheses",
                      &emitter_location::hypotheses,
                      "nuisance models the ellipse carries (1: the prior's only)")
        .def_readonly("model_spread_m",
                      &emitter_location::model_spread_m,
                      "RMS distance of the nuisance models' fixes from their mean")
        .def_readonly("wide_gust_weight",
                      &emitter_location::wide_gust_weight,
                      "evidence weight of the wide gust models (0..1)")
        .def_readonly("off_height_weight",
                      &emitter_location::off_height_weight,
                      "evidence weight of the heights the altimeter's error allows "
                      "(0..1)")
        .def_readonly("gust_rms_mps",
                      &emitter_location::gust_rms_mps,
                      "RMS of the gust states the fit found (m/s per axis)")
        .def_readonly("far_excess",
                      &emitter_location::far_excess,
                      "how much worse a plane wave (an emitter far away) explains the "
                      "data than this fix, in units of the noise variance (NaN: not "
                      "computed)")
        .def_readonly("unsure",
                      &emitter_location::unsure,
                      "published with a 95 % ellipse larger than the seeker's limit "
                      "(locate_max_axis_m) when the loiter's budget ran out")
        .def_readonly(
            "wandered",
            &emitter_location::wandered,
            "the fix of a loiter whose estimate wandered (strong gusts): a "
            "fit of all the loiter's data, published unsure, its ellipses sized "
            "by locator_nuisance.wander_radii_m()")
        .def("__repr__", [](const emitter_location& l) {
            if (!l.valid)
                return std::string("emitter_location(no fix)");
            char b[256];
            std::snprintf(b,
                          sizeof b,
                          "emitter_location(east_m=%.1f, north_m=%.1f, major_m=%.1f, "
                          "minor_m=%.1f, major50_m=%.1f, %s)",
                          l.east_m,
                          l.north_m,
                          l.major_m,
                          l.minor_m,
                          l.major50_m,
                          l.unsure ? "unsure" : "sure");
            return std::string(b);
        });
}

void bind_locator_nuisance_class(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<locator_nuisance>(
        m,
        "locator_nuisance",
        "What the fix does not know, carried into its ellipse: the fix refitted under "
        "the gust prior and two wide gust models (3 m/s at 15 s and 60 s) x the "
        "altimeter's reading and that reading +- altimeter_m, mixed by evidence; the "
        "ellipses' radii times factors calibrated on the gusts and the wind the fit "
        "found, and the user's scale95 and scale50.")
        .def(py::init<>(),
             "The defaults: 30 m of altimeter error, calibrated, the user's factors 1.")
        .def_readwrite("altimeter_m",
                       &locator_nuisance::altimeter_m,
                       "altimeter error carried (m, 0..1000; 0: the reading only)")
        .def_readwrite("calibrated",
                       &locator_nuisance::calibrated,
                       "False: the mixture's own chi-square contours, without the "
                       "calibrated factors")
        .def_readwrite("airspeed_mps",
                       &locator_nuisance::airspeed_mps,
                       "the vehicle's airspeed (m/s, 0.1..1000)")
        .def_readwrite("scale95",
                       &locator_nuisance::scale95,
                       "the user's radius factor of the 95 % ellipse (0.1..10)")
        .def_readwrite("scale50",
                       &locator_nuisance::scale50,
                       "the user's radius factor of the 50 % ellipse (0.1..10)")
        .def_static(
            "wander_radii_m",
            []() {
                const auto& k = locator_nuisance::WANDER_RADII_M;
                return std::vector<double>{ k[0], k[1] };
            },
            "The sizes [95 %, 50 %] (m, geometric mean of the semi-axes, at the "
            "default 25 m orbit and in proportion for wider ones) the seeker gives "
            "the ellipses of a loiter whose estimate wandered (emitter_location."
            "wandered), their direction and aspect kept, unless their own are "
            "smaller (WANDER_RADII_M in C++)")
        .def_static("whole_loiter_radii",
                    &locator_nuisance::whole_loiter_radii,
                    py::arg("height_m"),
                    py::arg("wind_fraction"),
                    "The sizes [95 %, 50 %] (m, as wander_radii_m) the seeker gives "
                    "the ellipses of a fit of all a loiter's data published unsure "
                    "(a wandering loiter's, or at the end of the loiter's budget) at "
                    "this height (emitter_location.altitude_m) and mean wind / "
                    "airspeed: larger low in the wind (under LOW_HEIGHT_M, at least "
                    "LOW_WIND_FRACTION); NaN counts as low")
        .def_static("factors",
                    &locator_nuisance::factors,
                    py::arg("gust_rms_mps"),
                    py::arg("wind_fraction"),
                    py::arg("height_m") = std::numeric_limits<double>::infinity(),
                    "The calibrated radius factors [k95, k50] of a fix whose fit "
                    "found this gust level (emitter_location.gust_rms_mps), mean "
                    "wind |wind| / airspeed_mps and height (emitter_location."
                    "altitude_m; default: not low); applied when calibrated is True, "
                    "before the user's scale95 and scale50. Fits under 70 m "
                    "(LOW_HEIGHT_M in C++) in a mean wind of at least 0.2 of the "
                    "airspeed (LOW_WIND_FRACTION) take the low factors, whatever "
                    "gusts they found. Never smaller in stronger gusts or wind, "
                    "or lower down; NaN counts as the worst (strongest, lowest).");
}

void bind_emitter_locator_class(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<emitter_locator>(
        m, "emitter_locator", "The emitter from the Doppler along a dead-reckoned path.")
        .def(py::init<double, double, double, double, double, double>(),
             py::arg("wavelength_m"),
             py::arg("search_radius_m") = 600.0,
             py::arg("gust_mps") = 0.0,
             py::arg("gust_tau_s") = 5.0,
             py::arg("altitude_m") = 0.0,
             py::arg("altitude_sigma_m") = 0.0,
             "A locator for the wavelength, a search radius around the path, a gust "
             "prior (std, correlation time) and a height prior (altitude, std; 0: none).")
        .def(
            "add",
            &emitter_locator::add,
            py::arg("time_s"),
            py::arg("x_m"),
            py::arg("y_m"),
            py::arg("vx_mps"),
            py::arg("vy_mps"),
            py::arg("freq_hz"),
            "One measurement: time (s); the vehicle's dead-reckoned position (m, x east, "
            "y north in its compass frame) and air velocity (m/s) then; the measured "
            "frequency (Hz, CFO included: the fit solves for it). Non-finite ones are "
            "skipped.")
        .def("__len__", &emitter_locator::size)
        .def("clear", &emitter_locator::clear, "Forget the samples.")
        .def("fit",
             &emitter_locator::fit,
             py::arg("vehicle_x_m"),
             py::arg("vehicle_y_m"),
             py::arg("nuisance") = false,
             py::call_guard<py::gil_scoped_release>(),
             "Fit everything added; vehicle_x/y: its dead-reckoned position at the fix. "
             "nuisance: the fix carries the models of set_nuisance (locator_nuisance).")
        .def("set_nuisance",
             &emitter_locator::set_nuisance,
             py::arg("nuisance"),
             "The nuisance models fit(..., nuisance=True) carries; ValueError outside "
             "locator_nuisance's ranges.")
        .def("nuisance", &emitter_locator::nuisance, "The nuisance models carried.")
        .def(
            "check_split",
            [](const emitter_locator& self, emitter_location l, double gate) {
                if (!(gate >= 0.0))
                    throw py::value_error("check_split: gate must be >= 0 (0: measure "
                                          "only)");
                self.check_split(l, gate);
                return l;
            },
            py::arg("location"),
            py::arg("gate") = 5.99,
            py::call_guard<py::gil_scoped_release>(),
            "The split check of `location` (a fit of everything added): the halves of "
            "the data in time fitted apart; returns a copy with `consistency` = their "
            "disagreement T (chi-square, 2 degrees of freedom for a right ellipse; -1: "
            "not run: an invalid fit or under 100 measurements per half) and, where T "
            "exceeds gate (> 0), the ellipse and wind_sigma_mps grown by sqrt(T / 2).");
}

} // namespace

void bind_arrival(py::module& m)
{
    bind_overflight_config_class(m);
    bind_doppler_amplitude_class(m);
    bind_overflight_detector_class(m);
    bind_emitter_location_class(m);
    bind_locator_nuisance_class(m);
    bind_emitter_locator_class(m);
}
