/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include <gr-rfseek/study.h>
#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace gr {
namespace rfseek {

namespace {

bool contains(const std::vector<std::string>& v, const std::string& k)
{
    return std::find(v.begin(), v.end(), k) != v.end();
}

double number(const std::string& key, const std::string& v)
{
    char* end = nullptr;
    const double d = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0')
        throw std::invalid_argument(key + ": cannot parse '" + v + "' as a number");
    return d;
}

} // namespace

bool study_point::is_key(const std::string& key)
{
    return contains(scenario::keys(), key) || contains(seeker_config::keys(), key) ||
           key == "interpolator" || key == "window" || key == "min_freq_hz" ||
           key == "max_freq_hz";
}

study_point::study_point(const std::string& preset,
                         const kv_list& given,
                         const std::string& sweep_key,
                         const std::string& sweep_value)
    : d_preset(preset), d_sweep_key(sweep_key), d_sweep_value(sweep_value), d_given(given)
{
    if (!preset.empty())
        d_sc.apply_preset(preset);
    for (const auto& kv : given)
        apply(kv.first, kv.second);
    if (!sweep_key.empty())
        apply(sweep_key, sweep_value);
}

void study_point::apply(const std::string& key, const std::string& value)
{
    if (contains(scenario::keys(), key))
        d_sc.set(key, value); // the scenario's fields feed the seeker via seeker_for()
    else if (contains(seeker_config::keys(), key)) {
        seeker_config probe;
        probe.set(key, value); // parse now, fail before the long run
        d_seeker_sets.emplace_back(key, value);
    } else if (key == "interpolator")
        d_est.interpolator = value;
    else if (key == "window")
        d_est.window = value;
    else if (key == "min_freq_hz")
        d_est.min_freq_hz = number(key, value);
    else if (key == "max_freq_hz")
        d_est.max_freq_hz = number(key, value);
    else {
        // Every key taken, by kind: a typo's neighbour is then in the message.
        auto join = [](const std::vector<std::string>& v, const auto& keep) {
            std::string out;
            for (const auto& k : v)
                if (keep(k))
                    out += (out.empty() ? "" : ", ") + k;
            return out;
        };
        const auto scen = scenario::keys();
        throw std::invalid_argument(
            "unknown parameter '" + key + "'. Scenario fields: " +
            join(scen, [](const std::string&) { return true; }) + ". Seeker constants: " +
            join(seeker_config::keys(),
                 [&](const std::string& k) { return !contains(scen, k); }) +
            ". Estimator settings: interpolator, window, min_freq_hz, max_freq_hz");
    }
}

void study_point::validate(const std::vector<std::string>& strategies) const
{
    d_sc.validate();
    for (const auto& st : strategies)
        simulation check(d_sc, seeker(st, d_sc.seed), d_est); // validates cfg and est
}

seeker_config study_point::seeker(const std::string& strategy, std::uint64_t seed) const
{
    scenario sc = d_sc;
    sc.seed = seed;
    seeker_config c = simulation::seeker_for(sc, strategy);
    for (const auto& kv : d_seeker_sets)
        c.set(kv.first, kv.second);
    return c;
}

run_summary study_point::run(const std::string& strategy, std::uint64_t seed) const
{
    scenario sc = d_sc;
    sc.seed = seed;
    return simulation(sc, seeker(strategy, seed), d_est).run(false).summary;
}

} // namespace rfseek
} // namespace gr
