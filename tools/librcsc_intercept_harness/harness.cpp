// Test harness (not part of the project): run librcsc's InterceptTable::update on given goalie states.
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>
#include <list>
#include <deque>
#include <map>
#include <set>
#include <algorithm>
#include <boost/shared_ptr.hpp>
#define private public
#define protected public
#include <rcsc/player/world_model.h>
#include <rcsc/player/intercept_table.h>
#include <rcsc/player/self_object.h>
#include <rcsc/player/ball_object.h>
#include <rcsc/player/player_object.h>
#include <rcsc/common/server_param.h>
#include <rcsc/common/player_param.h>
#include <rcsc/common/player_type.h>
#include <rcsc/game_mode.h>
#undef private
#undef protected
using namespace rcsc;

int main(int argc, char ** argv) {
    double prand = std::atof(argv[1]);
    double brand = std::atof(argv[2]);
    char msg[4096];
    std::snprintf(msg, sizeof(msg),
        "(server_param (stamina_max 8000)(stamina_inc_max 45)(player_rand %g)(ball_rand %g)(ball_speed_max 3)"
        "(player_speed_max 1.05)(player_decay 0.4)(inertia_moment 5)(dash_power_rate 0.006)(player_size 0.3)"
        "(kickable_margin 0.7)(kick_rand 0.1)(extra_stamina 50)(effort_init 1)(effort_min 0.6)(effort_dec 0.005)"
        "(effort_dec_thr 0.3)(effort_inc 0.01)(effort_inc_thr 0.6)(recover_init 1)(recover_dec_thr 0.3)"
        "(recover_dec 0.002)(recover_min 0.5)(stamina_capacity 130600)(max_dash_angle 180)(min_dash_angle -180)"
        "(dash_angle_step 45)(side_dash_rate 0.4)(back_dash_rate 0.6)(max_dash_power 100)(min_dash_power -100)"
        "(maxpower 100)(minpower -100)(maxmoment 180)(minmoment -180)(catchable_area_l 1.2)(catchable_area_w 1)"
        "(catch_probability 1)(ball_size 0.085)(ball_decay 0.94)(kick_power_rate 0.027)(tackle_cycles 10)"
        "(penalty_area_length 16.5)(penalty_area_width 40.32)(goal_width 14.02))", prand, brand);
    if (!ServerParam::instance().parse(msg, 14.0)) { std::fprintf(stderr, "parse failed\n"); }
    PlayerTypeSet::instance().resetDefaultType();
    const PlayerType * t0 = PlayerTypeSet::i().get(0);
    if (!t0) { std::fprintf(stderr, "no type 0\n"); return 1; }
    { const ServerParam & SP = ServerParam::i(); std::fprintf(stderr, "maxdash %g mindash %g step %g mina %g maxa %g stmax %g rdt %g bsm %g catch %.17g prand %g brand %g rsm %.17g ka %.17g side %g back %g maxp %g minp %g pdecay %g dpr %g effmax %g\n", SP.maxDashPower(), SP.minDashPower(), SP.dashAngleStep(), SP.minDashAngle(), SP.maxDashAngle(), SP.staminaMax(), SP.recoverDecThrValue(), SP.ballSpeedMax(), SP.catchableArea(), SP.playerRand(), SP.ballRand(), t0->realSpeedMax(), t0->kickableArea(), SP.sideDashRate(), SP.backDashRate(), SP.maxPower(), SP.minPower(), t0->playerDecay(), t0->dashPowerRate(), t0->effortMax()); }
    WorldModel wm;
    wm.M_our_side = RIGHT;
    wm.M_game_mode.M_type = GameMode::PlayOn;
    PlayerObject opp;
    int t = 1;
    double px, py, vx, vy, body, st, ef, rec, bx, by, wx, wy, ox, oy, ux, uy, ob;
    int has_opp, tackle, kick_opp, self_kick, lk;
    while (std::cin >> px >> py >> vx >> vy >> body >> st >> ef >> rec >> bx >> by >> wx >> wy >> has_opp
           >> ox >> oy >> ux >> uy >> ob >> tackle >> kick_opp >> self_kick >> lk) {
        wm.M_time = GameTime(t++, 0);
        wm.M_last_kicker_side = lk ? LEFT : RIGHT;
        SelfObject & s = wm.M_self;
        s.M_side = RIGHT; s.M_unum = 1; s.M_goalie = true; s.M_type = 0; s.M_player_type = t0;
        s.M_pos = Vector2D(px, py); s.M_pos_count = 0; s.M_vel = Vector2D(vx, vy); s.M_vel_count = 0;
        s.M_body = AngleDeg(body); s.M_body_count = 0;
        s.M_stamina.M_stamina = st; s.M_stamina.M_effort = ef; s.M_stamina.M_recovery = rec;
        s.M_stamina.M_capacity = 130600.0;
        s.M_kickable = (self_kick != 0);
        wm.M_ball.updateByFullstate(Vector2D(bx, by), Vector2D(wx, wy), s.M_pos);
        wm.M_ball.updateSelfRelated(s);
        wm.M_opponents_from_ball.clear();
        wm.M_opponents_from_self.clear();
        if (has_opp) {
            opp.M_side = LEFT; opp.M_unum = 11; opp.M_goalie = false; opp.M_type = 0; opp.M_player_type = t0;
            opp.M_pos = opp.M_seen_pos = Vector2D(ox, oy); opp.M_pos_count = opp.M_seen_pos_count = 0;
            opp.M_vel = opp.M_seen_vel = Vector2D(ux, uy); opp.M_vel_count = opp.M_seen_vel_count = 0;
            opp.M_body = AngleDeg(ob); opp.M_body_count = 0; opp.M_ghost_count = 0;
            opp.M_tackle_count = (tackle > 0 ? 9 - tackle : 1000);
            opp.M_dist_from_self = (Vector2D(ox, oy) - s.M_pos).r();
            wm.M_opponents_from_ball.push_back(&opp);
            wm.M_opponents_from_self.push_back(&opp);
        }
        wm.M_exist_kickable_opponent = (kick_opp != 0);
        wm.M_exist_kickable_teammate = false;
        wm.M_teammates_from_ball.clear();
        wm.M_teammates_from_self.clear();
        InterceptTable & it = *wm.M_intercept_table;
        it.update();
        const std::vector< InterceptInfo > & c = it.selfCache();
        std::printf("T %d %d %d %d\n", it.selfReachCycle(), it.opponentReachCycle(),
                    (int)c.size(), (int)it.M_ball_pos_cache.size());
        for (size_t i = 0; i < c.size(); ++i) {
            std::printf("E %d %d %d %.17g %.17g %.17g %.17g %.17g %.17g\n", c[i].mode() == InterceptInfo::NORMAL ? 0 : 1,
                        c[i].turnCycle(), c[i].dashCycle(), c[i].dashPower(), c[i].dashAngle().degree(),
                        c[i].selfPos().x, c[i].selfPos().y, c[i].ballDist(), c[i].stamina());
        }
    }
    return 0;
}
