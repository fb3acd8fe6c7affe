/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * model_loop: a noise-free stand-in for world + estimator shared by the seeker tests.
 */

#ifndef INCLUDED_RFSEEK_QA_MODEL_LOOP_H
#define INCLUDED_RFSEEK_QA_MODEL_LOOP_H

#include <gr-rfseek/seeker.h>
#include <gr-rfseek/world.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>

namespace gr {
namespace rfseek {
namespace qa {

// The vehicle is a point whose heading follows the commands (within an optional
// turn-rate limit); each slot's measurement is A cos(heading - beta) + cfo + drift t,
// exact, at the heading flown (beta may be moved between steps).
struct model_loop {
    seeker_config cfg;
    std::unique_ptr<seeker> sk;
    double beta = 0.0;  // bearing to the emitter
    double cfo = 250.0; // Hz at t = 0
    double drift = 0.0; // Hz/s
    double heading = 0.0;
    double commanded = 0.0;
    std::uint64_t slot = 0;
    int turning_slots = 0;

    explicit model_loop(seeker_config c, double start_heading) : cfg(c)
    {
        sk = seeker::make(cfg);
        heading = commanded = start_heading;
    }
    command step()
    {
        const double t = slot * cfg.slot_period_s;
        measurement m;
        m.slot = slot;
        m.time_s = t;
        m.freq_hz = cfg.max_doppler_hz() * std::cos(heading - beta) + cfo + drift * t;
        m.valid = true;
        m.has_heading = true;
        m.heading_rad = heading;
        const command c = sk->update(m);
        commanded = c.heading_rad;
        const double rate = cfg.turn_rate_rad_per_s * cfg.slot_period_s;
        const double turn = world::wrap(commanded - heading);
        if (rate > 0.0 && std::abs(turn) > rate) {
            heading = world::wrap(heading + std::copysign(rate, turn));
            ++turning_slots;
        } else
            heading = commanded;
        ++slot;
        return c;
    }
    // Runs n slots; returns the largest |theta_est - beta| over the last `tail` slots.
    double run(int n, int tail)
    {
        double worst = 0.0;
        for (int i = 0; i < n; ++i) {
            const command c = step();
            if (i >= n - tail)
                worst = std::max(worst, std::abs(world::wrap(c.theta_est_rad - beta)));
        }
        return worst;
    }
};

} // namespace qa
} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_QA_MODEL_LOOP_H */
