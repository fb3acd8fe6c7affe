/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The plane-wave test (emitter_location::far_excess, emitter_locator::fit with
 * nuisance): how much worse an emitter far away (a plane wave from the best bearing,
 * the same gust prior) explains a loiter's Doppler than the fix does. Synthetic orbits
 * 50 m up in a 4 m/s wind with slow strong gusts (2.5 m/s of 30 s, which can pull tight
 * fits by the vehicle far from the emitter): around the emitter no plane wave follows
 * the turning line of sight (excess in the hundreds), 3 km off one explains the data
 * as well as the fit (excess near zero or below); the fit without the nuisance does
 * not compute it.
 */

#include "arrival_fixtures.h"
#include <gr-rfseek/arrival.h>
#include <gr-rfseek/rng.h>
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>

using namespace gr::rfseek;
using namespace gr::rfseek::qa;

namespace {

/*
 * Three orbits of 25 m (fly_gusty_orbits) 50 m above the emitter's ground, gusts of
 * 2.5 m/s per axis and 30 s. The orbit starts (ox, oy) from the emitter. The locator has
 * the seeker's default priors (gusts 1.5 m/s at 4 s, the altimeter right +- 20 m).
 */
emitter_location orbit(std::uint64_t seed, double ox, double oy, bool nuisance = true)
{
    emitter_locator loc(LAMBDA, 600.0, 1.5, 4.0, 50.0, 20.0);
    rng g(seed, 51, 0);
    double gx = ox, gy = oy, qx, qy;
    fly_gusty_orbits(loc, g, 50.0, 25.0, 2.5, 30.0, gx, gy, qx, qy);
    return loc.fit(qx, qy, nuisance);
}

} // namespace

TEST(plane_wave, tells_an_orbit_by_the_emitter_from_one_kilometres_off)
{
    const int draws = 12;
    int near_refuted = 0, far_plausible = 0, near_fits = 0, far_fits = 0;
    double near_min = INFINITY;
    for (int d = 0; d < draws; ++d) {
        rng g(1000 + d, 52, 0);
        const double b = 2.0 * M_PI * g.uniform();
        const emitter_location near =
            orbit(d, 20.0 * std::cos(b), 20.0 * std::sin(b) - 25.0);
        const emitter_location far = orbit(d, 3000.0 * std::cos(b), 3000.0 * std::sin(b));
        if (near.valid) {
            ++near_fits;
            near_min = std::min(near_min, near.far_excess);
            near_refuted += near.far_excess >= 25.0;
        }
        if (far.valid) {
            ++far_fits;
            far_plausible += far.far_excess < 25.0;
        }
    }
    EXPECT_EQ(near_fits, draws);
    EXPECT_EQ(near_refuted, near_fits) << "smallest " << near_min;
    EXPECT_GE(far_fits, draws / 2);
    EXPECT_GE(far_plausible, far_fits - 1);
}

TEST(plane_wave, is_left_unknown_without_the_nuisance)
{
    const emitter_location l = orbit(3, 0.0, -25.0, false);
    ASSERT_TRUE(l.valid);
    EXPECT_TRUE(std::isnan(l.far_excess));
    EXPECT_TRUE(std::isfinite(orbit(3, 0.0, -25.0).far_excess));
}
