/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * autopilot_session: the rules of the seeker's MAVLink link to an autopilot, without
 * sockets or clocks of its own (the autopilot_link block and the tests drive it with
 * bytes and times). It follows the autopilot's heartbeat, mode and armed state; it
 * commands heading and airspeed only in the mode named and only while armed, by the
 * documented path of each autopilot family; it checks and retries command acks; it
 * stops commanding when the link falls silent; it reads only reports of the configured
 * system and component, and never passes position on. docs/live.md "Autopilot".
 */

#ifndef INCLUDED_RFSEEK_AUTOPILOT_SESSION_H
#define INCLUDED_RFSEEK_AUTOPILOT_SESSION_H

#include <gr-rfseek/api.h>
#include <gr-rfseek/mavlink.h>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace gr {
namespace rfseek {

//! The command path: which autopilot, as its documentation says for flight without GPS.
enum class autopilot_family {
    //! ArduPlane in GUIDED: MAV_CMD_GUIDED_CHANGE_HEADING and MAV_CMD_DO_CHANGE_SPEED.
    ardupilot_plane,
    //! ArduCopter in GUIDED_NOGPS: SET_ATTITUDE_TARGET (yaw, a forward pitch, thrust
    //! 0.5 = hold altitude), streamed.
    ardupilot_copter,
    //! PX4 in OFFBOARD: SET_ATTITUDE_TARGET streamed (at least 2 Hz, or PX4 leaves
    //! OFFBOARD).
    px4
};

//! The family named "ardupilot_plane" / "plane", "ardupilot_copter" / "copter", "px4";
//! std::invalid_argument naming the parameter otherwise.
RFSEEK_API autopilot_family autopilot_family_from_string(const std::string& name);
RFSEEK_API std::string to_string(autopilot_family f);

//! The custom_mode number of a mode name for a family ("GUIDED", "GUIDED_NOGPS",
//! "OFFBOARD", ...); std::invalid_argument listing the known names otherwise.
RFSEEK_API std::uint32_t autopilot_mode_number(autopilot_family f,
                                               const std::string& mode);
//! The family's mode for seeking: GUIDED (plane), GUIDED_NOGPS (copter), OFFBOARD (PX4).
RFSEEK_API std::string autopilot_default_mode(autopilot_family f);

struct RFSEEK_API autopilot_config {
    autopilot_family family = autopilot_family::ardupilot_plane;
    std::string mode;                  //!< empty: autopilot_default_mode(family)
    std::uint8_t target_system = 1;    //!< the autopilot's system id
    std::uint8_t target_component = 1; //!< the autopilot's component id
    std::uint8_t own_system = 1;       //!< ours: a companion computer of the same system
    std::uint8_t own_component = 191;  //!< MAV_COMP_ID_ONBOARD_COMPUTER
    double heartbeat_period_s = 1.0;   //!< our HEARTBEAT
    //! The link is lost when no frame of the autopilot arrived for this long (its
    //! telemetry flows at 10-50 Hz), or no HEARTBEAT for heartbeat_timeout_s.
    double link_timeout_s = 0.5;
    double heartbeat_timeout_s = 3.5;
    double ack_timeout_s = 0.3; //!< a COMMAND_LONG unanswered this long is sent again
    int retries = 3;            //!< sends after the first, then the command has failed
    double heading_deadband_deg = 0.5; //!< plane: a heading this close is not re-sent
    double command_min_period_s = 0.2; //!< plane: at most 5 heading commands a second
    double setpoint_period_s = 0.1;    //!< copter, PX4: the setpoint stream (10 Hz)
    double airspeed_mps = 0; //!< commanded airspeed; 0: the autopilot's own (cruise)
    //! Without a controller command for this long the link stops commanding (holding).
    double command_timeout_s = 2.0;
    //! Ask the autopilot for ATTITUDE at 20 Hz and VFR_HUD at 4 Hz when the link comes
    //! up (MAV_CMD_SET_MESSAGE_INTERVAL).
    bool request_streams = true;
    //! plane: MAV_CMD_GUIDED_CHANGE_HEADING param 3, the largest centripetal
    //! acceleration of the heading change (m/s^2; ArduPlane banks up to atan(a / g)).
    double heading_accel_mps2 = 6.0;
    double pitch_deg = 5; //!< copter, PX4: forward pitch of the setpoint
    double thrust = 0.5;  //!< copter, PX4: setpoint thrust
    /*!
     * Copter, PX4: the bank of a coordinated turn (deg, [0, 30]). A multirotor pitched
     * forward keeps its velocity when only its yaw turns: its track lags the yaw by
     * seconds. With a bank, the yaw setpoint turns toward the command at g tan(bank) /
     * turn_speed_mps, rolled into the turn so that the velocity turns with the yaw, as
     * a fixed wing's does. 0: the yaw steps to the command (the track follows late).
     */
    double turn_bank_deg = 0;
    //! Copter, PX4: the speed over the ground at pitch_deg (m/s), for the coordinated
    //! turn's rate; needed (> 0) when turn_bank_deg > 0.
    double turn_speed_mps = 0;
    /*!
     * PX4 (whose OFFBOARD attitude setpoints carry raw thrust, so that it holds no
     * height by itself): hold the barometric height (VFR_HUD) at which commanding
     * began, by the thrust: `thrust` (the hover thrust) + 0.02 per m of height error +
     * 0.002 per m s of its integral - 0.05 per m/s of climb, within [0.1, 0.9].
     */
    bool hold_altitude = false;
    /*!
     * The magnetic declination at the site (deg east of true north, [-180, 180]). An
     * autopilot without GPS never learns it (ArduPilot's COMPASS_DEC stays 0), so the
     * headings it flies and reports are magnetic. The session adds it to every reported
     * heading (nav is then from true north) and takes it from every commanded one, so
     * that the seeker, its wind forecast and its location fix are all from true north.
     * 0: the seeker works in the autopilot's frame, whatever it is.
     */
    double declination_deg = 0;
    //! Message signing: sign what we send and require signed frames from the link.
    std::optional<std::array<std::uint8_t, 32>> signing_key;
    std::uint8_t signing_link_id = 0;
    //! Seconds from the signing epoch (2015-01-01 UTC) to the session's time 0: signing
    //! timestamps are (t + offset) in 10 us units, kept strictly increasing.
    double signing_clock_offset_s = 0;
    //! Check every field; std::invalid_argument naming the first bad one and its range.
    void validate() const;
};

//! What the session reports about the link (the block's `status` port).
struct RFSEEK_API autopilot_status {
    //! "connecting" (no heartbeat yet), "holding" (linked, not commanding: see reason),
    //! "commanding", "lost" (was linked; silent now).
    std::string state = "connecting";
    std::string reason; //!< why holding / lost, or the last command failure
    bool armed = false;
    std::uint32_t custom_mode = 0;
    bool in_mode = false;
    double last_heartbeat = -1; //!< time of the autopilot's last HEARTBEAT (-1: none)
    std::uint64_t frames = 0;   //!< frames from the autopilot (its system and component)
    std::uint64_t heartbeats = 0, commands_sent = 0, commands_acked = 0,
                  commands_failed = 0, retries = 0, foreign = 0, statustext = 0;
    bool operator==(const autopilot_status& o) const
    {
        return state == o.state && reason == o.reason && armed == o.armed &&
               custom_mode == o.custom_mode && in_mode == o.in_mode;
    }
};

//! A heading report for the controller's `nav` port.
struct RFSEEK_API autopilot_nav {
    double heading_rad;       //!< module convention: counter-clockwise from east
    double time;              //!< the host time it arrived
    double airspeed_mps = -1; //!< the last VFR_HUD airspeed (-1: none yet)
};

class RFSEEK_API autopilot_session
{
public:
    explicit autopilot_session(const autopilot_config& config);

    //! Bytes from the link at host time t (seconds, any epoch, non-decreasing).
    void receive(const std::uint8_t* data, std::size_t n, double t);
    //! The controller's heading command (module convention, radians).
    void command(double heading_rad, double t);
    //! A new commanded airspeed (m/s, [0, 100]; 0: back to the autopilot's own), sent
    //! anew.
    void set_airspeed(double airspeed_mps);
    //! The controller is done (arrived, located, or gave up): stop commanding for good.
    void finish(double t);
    //! Advance to time t: heartbeats, commands, retries, setpoints and link checks.
    //! Returns the frames to send now.
    std::vector<std::vector<std::uint8_t>> poll(double t);

    //! Reports since the last call.
    std::vector<autopilot_nav> take_nav();
    //! Status snapshots, one per change of state or reason since the last call.
    std::vector<autopilot_status> take_status();
    //! Every frame received (valid, any system) and sent, with its time, for the
    //! telemetry log; cleared by the call.
    std::vector<std::pair<double, std::vector<std::uint8_t>>> take_log();

    const autopilot_status& status() const { return d_status; }
    const mavlink::parser::counters& parser_stats() const { return d_parser.stats(); }
    const autopilot_config& config() const { return d_cfg; }
    //! The autopilot's clock (s since its boot) in its last ATTITUDE, if any: a
    //! rehearsal's link runs on it (a simulator's clock at its own pace).
    std::optional<double> autopilot_time() const { return d_autopilot_time; }

private:
    struct pending {
        mavlink::message msg; //!< COMMAND_LONG or COMMAND_INT
        double sent_at;
        int sends;
    };
    static std::uint16_t command_of(const pending& p);
    //! The declination in radians (true = magnetic - declination, counter-clockwise).
    double declination() const { return d_cfg.declination_deg * M_PI / 180.0; }
    bool linked() const;
    bool streaming() const;
    void drop_pending(bool keep_link_requests);
    void queue_command_int(std::uint16_t cmd, const std::array<float, 4>& params);
    void queue_message(mavlink::message m);
    void settle_failure(std::uint16_t cmd, double t, const std::string& why);
    void plane_commands(double t);
    void send_pending(double t, std::vector<std::vector<std::uint8_t>>& out);
    void handle(const mavlink::frame& f, double t);
    void on_heartbeat(const mavlink::message& m, double t);
    void on_ack(const mavlink::message& m, double t);
    void update_state(double t);
    void set_state(const std::string& state, const std::string& reason);
    void report_status();
    void send(const mavlink::message& m,
              double t,
              std::vector<std::vector<std::uint8_t>>& out);
    void queue_command(std::uint16_t cmd, const std::array<float, 7>& params);
    mavlink::message setpoint() const;
    void advance_turn(double t);
    void hold_altitude(double dt);
    bool commanding() const { return d_status.state == "commanding"; }

    autopilot_config d_cfg;
    std::uint32_t d_mode_number;
    mavlink::parser d_parser;
    autopilot_status d_status;
    autopilot_status d_reported; //!< the last snapshot queued for take_status()
    std::uint8_t d_seq = 0;
    double d_last_frame = -1, d_last_sent_heartbeat = -1e300, d_last_setpoint = -1e300;
    double d_last_heading_sent_at = -1e300;
    std::optional<double> d_heading; //!< the controller's last command, autopilot frame
    std::optional<double> d_yaw_sp;  //!< coordinated turn: the yaw set now
    std::optional<double> d_attitude_yaw;   //!< the autopilot's last reported heading
    std::optional<double> d_autopilot_time; //!< its last ATTITUDE time_boot_ms (s)
    double d_roll_sp = 0, d_last_turn = -1; //!< coordinated turn: roll (rad), when
    std::optional<double> d_alt, d_alt_ref; //!< VFR_HUD height; hold_altitude's aim
    double d_climb = 0, d_alt_integral = 0, d_thrust_sp = 0.5;
    std::optional<double> d_heading_sent; //!< plane: last heading commanded
    bool d_speed_sent = false;
    bool d_speed_commanded = false; //!< a speed of ours is in force on the autopilot
    bool d_done = false;            //!< finish() was called
    double d_last_command = -1e300; //!< when the controller last commanded
    double d_heading_backoff = -1e300, d_speed_backoff = -1e300; //!< after a failure
    bool d_streams_requested = false;
    //! A frame other than a HEARTBEAT has come: the streams flow, and link_timeout_s
    //! applies; before, for heartbeat_timeout_s after the first heartbeat, only the
    //! heartbeat timeout (a port whose stream requests have not taken effect yet).
    bool d_streams_seen = false;
    double d_first_heartbeat = -1;
    std::vector<pending> d_pending; //!< COMMAND_LONGs awaiting acks
    std::uint64_t d_sign_time = 0;  //!< last signing timestamp used
    double d_airspeed = -1;
    std::vector<autopilot_nav> d_nav;
    std::vector<autopilot_status> d_status_out;
    std::vector<std::pair<double, std::vector<std::uint8_t>>> d_log;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_AUTOPILOT_SESSION_H */
