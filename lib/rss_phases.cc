/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include "rss_phases.h"
#include <Eigen/Dense>
#include <gr-rfseek/world.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gr {
namespace rfseek {
namespace rss {

namespace {

// Median of |p[i] - p[i - lag]| for i in [a + lag, b), finite pairs only (NaN: none).
double median_abs_lag(const std::vector<double>& p,
                      std::size_t a,
                      std::size_t b,
                      std::size_t lag)
{
    std::vector<double> v;
    for (std::size_t i = a + lag; i < b; ++i)
        if (std::isfinite(p[i]) && std::isfinite(p[i - lag]))
            v.push_back(std::abs(p[i] - p[i - lag]));
    if (v.empty())
        return NAN;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

} // namespace

direction_estimate estimate_direction(const std::vector<double>& power_db,
                                      const std::vector<double>& heading_rad,
                                      double sense,
                                      double radius_m)
{
    direction_estimate e;
    const std::size_t n = std::min(power_db.size(), heading_rad.size());
    // The first harmonic of the power over the position angle psi on the circle:
    // p = m + a cos(psi) + b sin(psi); (a, b) / radius is the mean-power gradient.
    Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
    Eigen::Vector3d atb = Eigen::Vector3d::Zero();
    std::size_t finite = 0;
    for (std::size_t k = 0; k < n; ++k) {
        if (!std::isfinite(power_db[k]) || !std::isfinite(heading_rad[k]))
            continue;
        const double psi = heading_rad[k] - sense * M_PI / 2.0;
        const Eigen::Vector3d row(1.0, std::cos(psi), std::sin(psi));
        ata += row * row.transpose();
        atb += row * power_db[k];
        ++finite;
    }
    if (finite < 30 || !(radius_m > 0.0))
        return e;
    const std::size_t half = 7, lag = 3;
    double best = INFINITY;
    std::size_t arg = n;
    std::vector<double> rates;
    for (std::size_t i = half + lag; i + half < n; ++i) {
        const double r = median_abs_lag(power_db, i - half - lag, i + half + 1, lag);
        if (!std::isfinite(r) || !std::isfinite(heading_rad[i]))
            continue;
        rates.push_back(r);
        if (r < best) {
            best = r;
            arg = i;
        }
    }
    const Eigen::Vector3d c = ata.ldlt().solve(atb);
    if (rates.empty() || !c.allFinite())
        return e;
    std::nth_element(rates.begin(), rates.begin() + rates.size() / 2, rates.end());
    e.axis_rad = world::wrap(heading_rad[arg]);
    const double gradient = std::atan2(c(2), c(1));
    const double along = std::hypot(c(1), c(2)) * std::cos(gradient - e.axis_rad);
    e.way_rad = along >= 0.0 ? e.axis_rad : world::wrap(e.axis_rad + M_PI);
    e.trend_db_per_m = std::abs(along) / radius_m;
    e.slow_rate_db = best;
    e.typical_rate_db = rates[rates.size() / 2];
    e.valid = true;
    return e;
}

run_monitor::run_monitor(int block_slots, int window, double fall_db)
    : d_block(block_slots), d_window(window), d_fall(fall_db), d_change(NAN)
{
    if (block_slots < 4 || block_slots > 100000)
        throw std::invalid_argument("block_slots = " + std::to_string(block_slots) +
                                    ": must be in [4, 100000]");
    if (window < 1 || window > 1000)
        throw std::invalid_argument("window = " + std::to_string(window) +
                                    ": must be in [1, 1000] blocks");
    if (!std::isfinite(fall_db) || fall_db < 0.0 || fall_db > 60.0)
        throw std::invalid_argument("fall_db = " + std::to_string(fall_db) +
                                    ": must be in [0, 60] dB");
}

void run_monitor::reset()
{
    d_in_block = d_valid = 0;
    d_sum = 0.0;
    d_change = NAN;
    d_means.clear();
}

bool run_monitor::add(double power_db)
{
    if (std::isfinite(power_db)) {
        d_sum += power_db;
        ++d_valid;
    }
    if (++d_in_block < d_block)
        return false;
    const bool counted = 4 * d_valid >= d_block;
    if (counted)
        d_means.push_back(d_sum / d_valid);
    d_in_block = d_valid = 0;
    d_sum = 0.0;
    const std::size_t w = static_cast<std::size_t>(d_window);
    if (!counted || d_means.size() < 2 * w)
        return false;
    double later = 0.0, earlier = 0.0;
    for (std::size_t i = 0; i < w; ++i) {
        later += d_means[d_means.size() - 1 - i];
        earlier += d_means[d_means.size() - 1 - w - i];
    }
    d_change = (later - earlier) / w;
    return d_change < -d_fall;
}

} // namespace rss
} // namespace rfseek
} // namespace gr
