/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(doppler_estimator.h) */
/* BINDTOOL_HEADER_FILE_HASH(29152da57febce08b08eaca59055c09f) */

#include <gr-rfseek/doppler_estimator.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <string>
#include <utility>

namespace py = pybind11;

namespace {

// Sample counts are unsigned in C++: a negative one from Python is a bad value
// (ValueError naming it), not a type pybind11 cannot convert.
std::shared_ptr<gr::rfseek::doppler_estimator>
make_checked(double samp_rate,
             int window_len,
             int fft_len,
             const std::string& window,
             const std::string& interpolator,
             const std::string& alignment,
             const std::string& tag_key,
             long long period,
             long long offset,
             double min_freq,
             double max_freq,
             double threshold_db,
             double pfa)
{
    for (const auto& [name, v] :
         { std::pair<const char*, long long>{ "period", period },
           std::pair<const char*, long long>{ "offset", offset } })
        if (v < 0)
            throw py::value_error(std::string("doppler_estimator: ") + name + " = " +
                                  std::to_string(v) + ": must be >= 0 (samples)");
    return gr::rfseek::doppler_estimator::make(samp_rate,
                                               window_len,
                                               fft_len,
                                               window,
                                               interpolator,
                                               alignment,
                                               tag_key,
                                               static_cast<std::uint64_t>(period),
                                               static_cast<std::uint64_t>(offset),
                                               min_freq,
                                               max_freq,
                                               threshold_db,
                                               pfa);
}

template <class Class>
void bind_receiver_faults(Class& cls)
{
    using gr::rfseek::doppler_estimator;
    cls.def("acquire_state",
            &doppler_estimator::acquire_state,
            "'acquire': 'search', 'confirm' or 'locked'; other alignments: ''.")
        .def("period_estimate",
             &doppler_estimator::period_estimate,
             "'acquire': the burst period the timing loop tracks (samples); else period.")
        .def("discontinuity_count",
             &doppler_estimator::discontinuity_count,
             "rx_time tags that disagreed with the sample count (samples lost, or the "
             "clock set back).")
        .def("carriers",
             &doppler_estimator::carriers,
             "'acquire': the continuous carriers (interferers) found and removed, Hz.")
        .def("set_full_scale",
             &doppler_estimator::set_full_scale,
             py::arg("full_scale"),
             "The receiver's full scale in the input's units (1.0 for radios' complex64; "
             "0: no clipping check). Windows peaking at 95 % of it are clipped and never "
             "valid; messages carry peak_dbfs and clipped (GRC callback).")
        .def(
            "full_scale", &doppler_estimator::full_scale, "The full scale set (0: none).")
        .def("clipped_count",
             &doppler_estimator::clipped_count,
             "Windows found clipped (full_scale > 0).");
}

} // namespace

void bind_doppler_estimator(py::module& m)
{
    using gr::rfseek::doppler_estimator;
    auto cls =
        py::class_<doppler_estimator,
                   gr::sync_block,
                   gr::block,
                   gr::basic_block,
                   std::shared_ptr<doppler_estimator>>(
            m,
            "doppler_estimator",
            "Windowed, zero-padded FFT frequency estimator: one 'meas' message per "
            "window.")
            .def(
                py::init(&make_checked),
                py::arg("samp_rate"),
                py::arg("window_len"),
                py::arg("fft_len"),
                py::arg("window") = "rectangular",
                py::arg("interpolator") = "parabolic",
                py::arg("alignment") = "tag",
                py::arg("tag_key") = "rfseek_beacon",
                py::arg("period") = 0,
                py::arg("offset") = 0,
                py::arg("min_freq") = 0.0,
                py::arg("max_freq") = 0.0,
                py::arg("threshold_db") = 2.0,
                py::arg("pfa") = 0.0,
                "\\param samp_rate sample rate (Hz, > 0) \\param window_len N samples "
                "per "
                "window (3 <= N <= fft_len) \\param fft_len N_FFT (>= 4) \\param window "
                "\"rectangular\", \"hann\" or \"blackman_harris\" \\param interpolator "
                "\"parabolic\" (paper eq. 3), \"newton\" (ML) or \"log_parabolic\" "
                "\\param "
                "alignment \"tag\", \"periodic\", \"energy\" or \"acquire\" \\param "
                "tag_key key of the aligning tags (alignment \"tag\") \\param period "
                "samples between window starts (alignment \"periodic\", >= window_len; "
                "\"acquire\": the beacon's nominal period, > window_len) \\param offset "
                "first window "
                "start (alignment \"periodic\", >= 0) \\param min_freq, max_freq search "
                "band in Hz; equal values search the whole band \\param threshold_db "
                "burst "
                "detection level over the noise floor (alignment        \"energy\", > 0 "
                "dB) "
                "\\param pfa false-alarm probability of the per-window detection test: 0 "
                "(no test) or in [1e-12, 0.5]; \"acquire\" always tests (0 means 1e-3)")
            .def("window", &doppler_estimator::window, "The window's name.")
            .def("interpolator",
                 &doppler_estimator::interpolator,
                 "The peak interpolator's name.")
            .def("alignment",
                 &doppler_estimator::alignment,
                 "How windows are found: 'tag', 'periodic', 'energy' or 'acquire'.")
            .def("min_freq",
                 &doppler_estimator::min_freq,
                 "Lower edge of the search band (Hz).")
            .def("max_freq",
                 &doppler_estimator::max_freq,
                 "Upper edge of the search band (Hz).")
            .def(
                "window_count",
                &doppler_estimator::window_count,
                "Windows measured / of them invalid / of them cut short by the next tag.")
            .def("invalid_count",
                 &doppler_estimator::invalid_count,
                 "Windows whose estimate was not valid.")
            .def("truncated_count",
                 &doppler_estimator::truncated_count,
                 "Windows cut short by the end of the stream or a new burst.")
            .def("set_window",
                 &doppler_estimator::set_window,
                 py::arg("window"),
                 "Change the window (GRC callback).")
            .def("set_interpolator",
                 &doppler_estimator::set_interpolator,
                 py::arg("interpolator"),
                 "Change the peak interpolator (GRC callback).")
            .def("threshold_db",
                 &doppler_estimator::threshold_db,
                 "Burst detection level over the noise floor (dB, alignment 'energy').")
            .def("set_threshold_db",
                 &doppler_estimator::set_threshold_db,
                 py::arg("threshold_db"),
                 "Change the burst detection level (dB).")
            .def(
                "set_band",
                &doppler_estimator::set_band,
                py::arg("min_freq"),
                py::arg("max_freq"),
                "Search only [min, max] Hz (GRC callback; equal values: the whole band).")
            .def("samp_rate",
                 &doppler_estimator::samp_rate,
                 "The rate frequencies are measured at (Hz): samp_rate, or the latest "
                 "rx_rate tag's or set_samp_rate's.")
            .def("set_samp_rate",
                 &doppler_estimator::set_samp_rate,
                 py::arg("samp_rate"),
                 "A new sample rate (> 0; the search band must still fit), e.g. the rate "
                 "a "
                 "device granted (GRC callback). Raises ValueError naming it.")
            .def("pfa",
                 &doppler_estimator::pfa,
                 "Detection test's false-alarm probability (0: no test).")
            .def("set_pfa",
                 &doppler_estimator::set_pfa,
                 py::arg("pfa"),
                 "0 turns the test off (not under 'acquire'); else in [1e-12, 0.5] (GRC "
                 "callback).");
    bind_receiver_faults(cls);
}
