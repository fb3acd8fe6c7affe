/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include "angle.h"
#include "turn_model.h"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gr {
namespace rfseek {

namespace {
constexpr double G = 9.80665; // m/s^2
constexpr int SUBSTEPS = 8;   // per step of the coordinated turn
} // namespace

double turn_limits::max_rate() const
{
    const double bank_rate =
        bank_rad > 0.0 ? G * std::tan(bank_rad) / std::max(speed_mps, 1e-9) : 0.0;
    if (rate_rad_per_s > 0.0 && bank_rate > 0.0)
        return std::min(rate_rad_per_s, bank_rate);
    return std::max(rate_rad_per_s, bank_rate);
}

double turn_limits::max_bank() const
{
    const double w = max_rate();
    return w > 0.0 ? std::atan(w * std::max(speed_mps, 1e-9) / G) : 0.0;
}

double turn_limits::min_radius_m() const
{
    const double w = max_rate();
    return w > 0.0 ? speed_mps / w : 0.0;
}

double turn_limits::change_time_s(double angle_rad) const
{
    const double a = std::abs(angle_rad);
    const double w = max_rate();
    if (w <= 0.0)
        return 0.0;
    if (!rolls())
        return a / w;
    // Roll in at p, hold the bank, roll out at p: each roll turns (g / (v p)) (-ln cos).
    const double k = G / std::max(speed_mps, 1e-9), p = roll_rate_rad_per_s;
    const double bm = max_bank();
    const double rolls_turn = 2.0 * (k / p) * -std::log(std::cos(bm));
    if (rolls_turn >= a) // the bank limit is never reached
        return 2.0 * std::acos(std::exp(-a * p / (2.0 * k))) / p;
    return 2.0 * bm / p + (a - rolls_turn) / (k * std::tan(bm));
}

coordinated_turn::coordinated_turn(const turn_limits& lim,
                                   double heading_rad,
                                   double bank_rad)
    : d_lim(lim), d_heading(wrap_remainder(heading_rad)), d_bank(bank_rad)
{
}

void coordinated_turn::set_heading(double heading_rad)
{
    d_heading = wrap_remainder(heading_rad);
    d_bank = 0.0;
    d_turning = false;
}

void coordinated_turn::step(double command_rad, double dt)
{
    if (!d_lim.rolls())
        throw std::logic_error(
            "coordinated_turn::step: needs a bank and a roll-rate limit "
            "(a plain turn-rate limit is the world's arc)");
    const double target = wrap_remainder(command_rad);
    d_px = d_py = 0.0;
    // Coordinated turn. Working in the turn's sense (b > 0 banks toward the command),
    // each sub-step takes the largest of: roll further in, hold the bank, roll out,
    // such that rolling out afterwards (stop(b) = (g / (v p)) (-ln cos b)) still ends
    // on the command.
    const double k = G / std::max(d_lim.speed_mps, 1e-9);
    const double p = d_lim.roll_rate_rad_per_s, bm = d_lim.max_bank();
    const double h = dt / SUBSTEPS, dphi = p * h;
    const auto stop = [&](double b) {
        return std::copysign((k / p) * -std::log(std::cos(b)), b);
    };
    const auto turned = [&](double b0, double b1) {
        return 0.5 * k * h * (std::tan(b0) + std::tan(b1));
    };
    for (int i = 0; i < SUBSTEPS; ++i) {
        const double e = wrap_remainder(target - d_heading);
        const double sense = e >= 0.0 ? 1.0 : -1.0, left = std::abs(e);
        const double b = sense * d_bank;
        // Aligned within what one sub-step at the smallest bank turns: level out.
        if (left <= k * std::tan(dphi) * h && std::abs(d_bank) <= dphi) {
            d_heading = target;
            d_bank = 0.0;
            d_px += h * std::cos(d_heading);
            d_py += h * std::sin(d_heading);
            continue;
        }
        double b1 = std::min(b + dphi, bm);
        if (turned(b, b1) + stop(b1) > left) {
            b1 = std::min(b, bm);
            if (b1 <= 0.0 || turned(b, b1) + stop(b1) > left)
                b1 = std::max(b - dphi, -bm);
        }
        const double h1 = d_heading + sense * turned(b, b1);
        const double mid = 0.5 * (d_heading + h1);
        d_px += h * std::cos(mid);
        d_py += h * std::sin(mid);
        d_heading = wrap_remainder(h1);
        d_bank = sense * b1;
    }
    d_turning = d_heading != target || d_bank != 0.0;
}

} // namespace rfseek
} // namespace gr
