/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * turn_model: how the vehicle's heading follows a command (docs/world.md "Turns").
 * Three airframes, from the same limits the world and the seekers are given:
 * - no limit: the heading jumps to the command (the paper's);
 * - a turn-rate limit omega (turn_rate_rad_per_s, and/or a bank limit with an
 *   instantaneous roll: omega = g tan(bank) / v): an arc at omega until aligned;
 * - a coordinated turn (bank limit and roll-rate limit p): the turn rate is
 *   g tan(phi) / v, the bank phi moves at most p, so a heading change first waits for
 *   the roll. The bank is steered toward sign(e) min(bank, phi_stop(|e|)), where
 *   phi_stop(x) = acos(exp(-x p v / g)) is the bank from which rolling out at p turns
 *   exactly x more (the integral of g tan(phi) / v as phi falls to 0 at rate p):
 *   the heading reaches the command without overshoot, bank-limited in between.
 * Internal to the library; the closed forms below are checked against the stepped
 * model in lib/qa/qa_turn_model.cc.
 */

#ifndef INCLUDED_RFSEEK_TURN_MODEL_H
#define INCLUDED_RFSEEK_TURN_MODEL_H

#include <gr-rfseek/api.h>

namespace gr {
namespace rfseek {

struct RFSEEK_API turn_limits {
    double rate_rad_per_s = 0.0;      //!< turn-rate limit; 0 = none
    double bank_rad = 0.0;            //!< bank limit; 0 = none
    double roll_rate_rad_per_s = 0.0; //!< roll-rate limit; 0 = instantaneous roll
    double speed_mps = 10.0;          //!< airspeed (turn rate = g tan(bank) / v)

    //! The steady turn-rate limit: min(rate, g tan(bank) / v); 0 = unlimited.
    double max_rate() const;
    //! The bank the steady limit allows (rad); 0 = unlimited.
    double max_bank() const;
    //! True when the bank follows a roll-rate limit (a coordinated turn).
    bool rolls() const { return bank_rad > 0.0 && roll_rate_rad_per_s > 0.0; }
    //! True when heading changes take time.
    bool limited() const { return max_rate() > 0.0; }
    //! Time (s) to change the heading by |angle| from wings level to wings level.
    double change_time_s(double angle_rad) const;
    //! Radius (m) of the tightest steady turn; 0 = unlimited.
    double min_radius_m() const;
};

class RFSEEK_API coordinated_turn
{
public:
    coordinated_turn(const turn_limits& lim, double heading_rad, double bank_rad = 0.0);

    /*!
     * Fly dt toward the commanded heading in eight sub-steps; the air path of the step
     * per unit airspeed is then in path_x() / path_y(). Needs limits().rolls(): the
     * plain rate-limited arc is flown by world::advance and the strategies' own model.
     */
    void step(double command_rad, double dt);

    double heading_rad() const { return d_heading; }
    double bank_rad() const { return d_bank; }
    //! True while the heading differs from the last command or the wings are banked.
    bool turning() const { return d_turning; }
    double path_x() const { return d_px; }
    double path_y() const { return d_py; }
    void set_heading(double heading_rad);
    const turn_limits& limits() const { return d_lim; }

private:
    turn_limits d_lim;
    double d_heading, d_bank = 0.0, d_px = 0.0, d_py = 0.0;
    bool d_turning = false;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_TURN_MODEL_H */
