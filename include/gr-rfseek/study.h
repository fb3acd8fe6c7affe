/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * study_point: one point of a Monte Carlo study (a preset, the given KEY=VALUE settings,
 * a sweep value) resolved into what each run uses. rfseek-montecarlo's threads and its
 * Dask workers both run every row through study_point::run, so the rows agree per seed
 * whatever the backend. Plain C++.
 */

#ifndef INCLUDED_RFSEEK_STUDY_H
#define INCLUDED_RFSEEK_STUDY_H

#include <gr-rfseek/api.h>
#include <gr-rfseek/scenario.h>
#include <gr-rfseek/seeker.h>
#include <gr-rfseek/simulation.h>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace gr {
namespace rfseek {

class RFSEEK_API study_point
{
public:
    using kv_list = std::vector<std::pair<std::string, std::string>>;

    /*!
     * The preset (empty: the reference scenario) first, then the given settings in order,
     * then the sweep value (sweep_key empty: none). A setting is a scenario field (any of
     * scenario::keys()), a seeker constant (any of seeker_config::keys()) or an estimator
     * setting (interpolator, window, min_freq_hz, max_freq_hz). Throws
     * std::invalid_argument for an unknown preset or key or an unparsable value.
     */
    study_point(const std::string& preset = "",
                const kv_list& given = {},
                const std::string& sweep_key = "",
                const std::string& sweep_value = "");

    //! Ranges of the scenario and of each strategy's configuration (throws, naming it).
    void validate(const std::vector<std::string>& strategies) const;

    //! The seeker configuration of one run: seeker_for(scenario with seed), then the
    //! seeker constants given.
    seeker_config seeker(const std::string& strategy, std::uint64_t seed) const;

    //! One run of the closed loop, scenario seed = seed (no records kept).
    run_summary run(const std::string& strategy, std::uint64_t seed) const;

    const std::string& preset() const { return d_preset; }
    const std::string& sweep_key() const { return d_sweep_key; }
    const std::string& sweep_value() const { return d_sweep_value; }
    const kv_list& given() const { return d_given; }
    const scenario& scenario_config() const { return d_sc; }
    const kv_list& seeker_sets() const { return d_seeker_sets; }
    const estimator_config& estimator() const { return d_est; }

    //! Whether key is a setting a study point accepts.
    static bool is_key(const std::string& key);

private:
    void apply(const std::string& key, const std::string& value);

    std::string d_preset, d_sweep_key, d_sweep_value;
    kv_list d_given;
    scenario d_sc;
    kv_list d_seeker_sets;
    estimator_config d_est;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_STUDY_H */
