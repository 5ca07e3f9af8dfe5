/* hfo2d._accel: optional compiled kernels for hfo2d's hottest pure-Python functions.
 *
 * Every kernel here is a port of a Python function of hfo2d that stays the reference (and the fallback when this
 * extension is not built, or when HFO2D_PURE_PYTHON=1): tests/hfo2d/test_accel_reference.py runs both on the same
 * inputs and compares the results bit for bit. To give the same doubles, each kernel does the same IEEE operations
 * in the same order as its Python original:
 *   - setup.py compiles this file with -ffp-contract=off (no fused multiply-add) and without -ffast-math;
 *   - sin, cos, atan2, asin, sqrt, fmod, floor, ceil, log10 and pow are libm's, as Python's math module and float
 *     operators call them (math.atan2's special cases equal C99's for finite arguments);
 *   - hypot is NOT libm's: CPython's math.hypot has its own algorithm since 3.10 (on glibc 2.36 about 0.4 % of
 *     random (x, y) pairs differ from libm's hypot by an ulp), so the kernels compute CPython 3.11's algorithm
 *     when built for 3.11 and call math.hypot itself otherwise (py_hypot below);
 *   - a number is printed and parsed with CPython's own PyOS_double_to_string / PyOS_string_to_double, as
 *     float(f"{x:.6g}") does.
 * Positions are assumed finite (no NaN): sorting compares with <, as Python's sort does, by a stable insertion
 * sort.
 *
 * Objects (hfo2d.physics.PlayerState / BallState, slotted dataclasses) are read and written through their slots
 * (read_attr / write_attr), falling back to the generic attribute protocol for anything else.
 *
 * The kernels, in file order: CPython's hypot; fullstate_value; the low-level features; the intercept table's
 * reach of the other players, predictFinal and the short steps of the self intercept, the ball path; the NPCs'
 * fullstate conversions; one object's move, the stamina update and the overlap test of World.step; the flat
 * action decode. Each section names its Python reference and its librcsc / rcssserver source.
 *
 * Units are rcssserver's: metres, metres per cycle, degrees.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <structmember.h> /* T_OBJECT_EX, READ_RESTRICTED */

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* math.hypot, looked up at import (see the header comment) */
static PyObject *math_hypot = NULL;

/* hypot(x, y) by calling math.hypot; -1.0 with an exception set on failure. */
static double
call_math_hypot(double x, double y)
{
    PyObject *args[2];
    args[0] = PyFloat_FromDouble(x);
    args[1] = PyFloat_FromDouble(y);
    if (args[0] == NULL || args[1] == NULL) {
        Py_XDECREF(args[0]);
        Py_XDECREF(args[1]);
        return -1.0;
    }
    PyObject *result = PyObject_Vectorcall(math_hypot, args, 2, NULL);
    Py_DECREF(args[0]);
    Py_DECREF(args[1]);
    if (result == NULL) {
        return -1.0;
    }
    double value = PyFloat_AsDouble(result);
    Py_DECREF(result);
    return value;
}

#if PY_VERSION_HEX >= 0x030B0000 && PY_VERSION_HEX < 0x030C0000
#define NATIVE_HYPOT 1
/* CPython 3.11's math.hypot for two finite numbers whose larger magnitude is a normal double (Modules/mathmodule.c
 * vector_norm, 3.11 branch; its comments describe the method): the coordinates scaled by a power of two so that
 * the larger lies in [0.5, 1), each split in halves of 26 bits (Veltkamp, T27 = 2**27 + 1) so that their squares
 * and cross products are exact, those summed with the rounding errors kept (frac1, frac2, frac3), the square root
 * taken, and one differential correction of h against the exact sum. Written from that description; checked
 * against math.hypot on millions of pairs (tests/hfo2d/test_accel_reference.py). Other versions of CPython use
 * other algorithms, so they call math.hypot itself. */
static double
hypot_311(double ax, double ay, double max)
{
    const double T27 = 134217729.0;
    int max_e;
    frexp(max, &max_e);
    double scale = ldexp(1.0, -max_e);
    double csum = 1.0, frac1 = 0.0, frac2 = 0.0, frac3 = 0.0;
    double coordinates[2] = {ax, ay};
    for (int i = 0; i < 2; i++) {
        double x = coordinates[i] * scale;
        double t = x * T27;
        double hi = t - (t - x);
        double lo = x - hi;
        double old = csum;
        double term = hi * hi;
        csum += term;
        frac1 += (old - csum) + term;
        term = 2.0 * hi * lo;
        old = csum;
        csum += term;
        frac2 += (old - csum) + term;
        frac3 += lo * lo;
    }
    double h = sqrt(csum - 1.0 + (frac1 + frac2 + frac3));
    double t = h * T27;
    double hi = t - (t - h);
    double lo = h - hi;
    double old = csum;
    double term = -hi * hi;
    csum += term;
    frac1 += (old - csum) + term;
    term = -2.0 * hi * lo;
    old = csum;
    csum += term;
    frac2 += (old - csum) + term;
    term = -lo * lo;
    old = csum;
    csum += term;
    frac3 += (old - csum) + term;
    double correction = csum - 1.0 + (frac1 + frac2 + frac3);
    return (h + correction / (2.0 * h)) / scale;
}
#else
#define NATIVE_HYPOT 0
#endif

/* hypot(x, y) as Python's math.hypot computes it; -1.0 with an exception set on failure (a distance is never
 * negative, so the caller can test for it). */
static double
py_hypot(double x, double y)
{
#if NATIVE_HYPOT
    double ax = fabs(x), ay = fabs(y);
    double max = ax > ay ? ax : ay;
    if (max == 0.0) {
        return 0.0;
    }
    if (max >= 4.0 * DBL_MIN && max <= DBL_MAX) { /* normal and finite (NaN fails both tests) */
        return hypot_311(ax, ay, max);
    }
#endif
    return call_math_hypot(x, y); /* subnormal, infinite or NaN magnitudes: rare, and Python's own rules */
}

static PyObject *
accel_hypot(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 2) {
        PyErr_SetString(PyExc_TypeError, "hypot(x, y)");
        return NULL;
    }
    double x = PyFloat_AsDouble(args[0]);
    double y = PyFloat_AsDouble(args[1]);
    if (PyErr_Occurred()) {
        return NULL;
    }
    double h = py_hypot(x, y);
    if (h < 0.0) {
        return NULL;
    }
    return PyFloat_FromDouble(h);
}

/* ------------------------------------------------------------------------------------------------------------
 * fullstate_value (port of hfo2d.agent2d.goalie.fullstate_value_python)
 *
 * A number as librcsc reads it from rcssserver's fullstate message: printed with 6 significant digits (%g) and
 * parsed back (rcssserver 15 serializerplayerstdv1.cpp serializeFSBegin sets precision(6); librcsc
 * fullstate_sensor.cpp parses with strtod). The Python function's fast paths (1e-16 <= |x| < 10000, and the tiny
 * numbers below 1e-16) are ported with the same operations (its docstring proves they equal the string round
 * trip); every other input takes the string round trip itself, as the Python does. The Python's dict memo is
 * replaced by a small direct-mapped memo of the slow paths only (the fast path costs less than a lookup).
 * ------------------------------------------------------------------------------------------------------------ */
static double pow10_exact[23];    /* 10**0 .. 10**22, exact doubles */
static double pow10_nearest[309]; /* the doubles nearest to 10**0 .. 10**308 (float(10**k)) */

static int
fullstate_string_round_trip(double x, double *out)
{
    char *text = PyOS_double_to_string(x, 'g', 6, 0, NULL);
    if (text == NULL) {
        return -1;
    }
    double value = PyOS_string_to_double(text, NULL, NULL);
    PyMem_Free(text);
    if (value == -1.0 && PyErr_Occurred()) {
        return -1;
    }
    *out = value;
    return 0;
}

/* The string round trip's results, by the input's bits (direct-mapped): the tiny and rare numbers that take it are
 * converted by every NPC in the same cycle. */
#define ROUND_TRIP_MEMO_SIZE 1024
static struct {
    uint64_t bits;
    double value;
    int used;
} round_trip_memo[ROUND_TRIP_MEMO_SIZE];

static int
fullstate_number(double x, double *out)
{
    if (x == 0.0) {
        *out = x; /* keeps the sign of a zero */
        return 0;
    }
    double a = x < 0.0 ? -x : x;
    if (1.0e-16 <= a && a < 10000.0) {
        double s;
        if (a >= 1.0) {
            s = a < 10.0 ? 100000.0 : (a < 100.0 ? 10000.0 : (a < 1000.0 ? 1000.0 : 100.0));
        }
        else if (a >= 0.001) {
            s = a >= 0.1 ? 1000000.0 : (a >= 0.01 ? 10000000.0 : 100000000.0);
        }
        else {
            s = pow10_exact[5 - (int)floor(log10(a))]; /* 10**9 .. 10**22 */
        }
        double p = a * s;
        double f = fmod(p, 1.0); /* Python's p % 1.0 for a positive p */
        if (100000.001 <= p && p < 999999.0 && !(0.499999 < f && f < 0.500001)) {
            double y = (f > 0.5 ? (p - f) + 1.0 : p - f) / s;
            *out = x < 0.0 ? -y : y;
            return 0;
        }
    }
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    size_t slot = (size_t)((bits ^ (bits >> 29) ^ (bits >> 47)) & (ROUND_TRIP_MEMO_SIZE - 1));
    if (round_trip_memo[slot].used && round_trip_memo[slot].bits == bits) {
        *out = round_trip_memo[slot].value;
        return 0;
    }
    double y;
    int done = 0;
    if (a < 1.0e-16 && a == a) {
        /* the Python's path for 5e-324 <= |x| < 1e-16: the scale 10**digits is past the exact doubles, p is |x|
         * times its nearest double (or 1e22 times the nearest of 10**(digits - 22)), and the printed number
         * m / 10**digits is rounded once to the nearest double: here by parsing "me-digits" (correctly rounded,
         * as CPython's int true division is) */
        int digits = 5 - (int)floor(log10(a)); /* 22 < digits <= 329 */
        double p = digits <= 308 ? a * pow10_nearest[digits] : a * 1.0e22 * pow10_nearest[digits - 22];
        double f = fmod(p, 1.0);
        if (100000.001 <= p && p < 999999.0 && !(0.499999 < f && f < 0.500001)) {
            long long m = (long long)p + (f > 0.5 ? 1 : 0);
            char text[48];
            snprintf(text, sizeof text, "%llde-%d", m, digits);
            y = PyOS_string_to_double(text, NULL, NULL);
            if (y == -1.0 && PyErr_Occurred()) {
                return -1;
            }
            if (x < 0.0) {
                y = -y;
            }
            done = 1;
        }
    }
    if (!done && fullstate_string_round_trip(x, &y) < 0) {
        return -1;
    }
    round_trip_memo[slot].bits = bits;
    round_trip_memo[slot].value = y;
    round_trip_memo[slot].used = 1;
    *out = y;
    return 0;
}

static PyObject *
accel_fullstate_value(PyObject *module, PyObject *arg)
{
    double x = PyFloat_AsDouble(arg);
    if (x == -1.0 && PyErr_Occurred()) {
        return NULL;
    }
    double y;
    if (fullstate_number(x, &y) < 0) {
        return NULL;
    }
    return PyFloat_FromDouble(y);
}

/* ------------------------------------------------------------------------------------------------------------
 * low_level_feature_list (port of hfo2d.features.low_level_feature_list_python without opponent_control)
 *
 * HFO's paper-era LowLevelFeatureExtractor layout (HFO src/lowlevel_feature_extractor.cpp before July 2017;
 * hfo_reference §2, §9): 58 basic features, then an 8-feature block per teammate and per opponent, each group
 * sorted by squared distance from the observer (stable), a player listed only while x > 0.
 * ------------------------------------------------------------------------------------------------------------ */

/* The normalisers of hfo2d.features; features.py checks at import that they equal its own (FEATURE_CONSTANTS). */
#define PITCH_HALF_LENGTH 52.5
#define PITCH_HALF_WIDTH 34.0
#define GOAL_HALF_WIDTH 7.01
#define PENALTY_AREA_X 36.0
#define PENALTY_AREA_HALF_WIDTH 20.16
#define SELF_SPEED_MAX 0.46
#define PLAYER_SPEED_MAX 0.75
#define BALL_SPEED_MAX 5.0
#define STAMINA_MAX 8000.0
static double MAX_HFO_DIST; /* sqrt(52.5**2 + 34**2), set at import */
#define NUM_BASIC_FEATURES 58
#define FEATURES_PER_PLAYER 8
#define MAX_GROUP 64 /* players per side handled here; a larger group is refused */

/* the landmarks in hfo2d.features.LANDMARKS order */
static const double LANDMARKS[11][2] = {
    {PITCH_HALF_LENGTH, 0.0},
    {PITCH_HALF_LENGTH, -GOAL_HALF_WIDTH},
    {PITCH_HALF_LENGTH, GOAL_HALF_WIDTH},
    {PENALTY_AREA_X, 0.0},
    {PENALTY_AREA_X, -PENALTY_AREA_HALF_WIDTH},
    {PENALTY_AREA_X, PENALTY_AREA_HALF_WIDTH},
    {0.0, 0.0},
    {0.0, -PITCH_HALF_WIDTH},
    {PITCH_HALF_LENGTH, -PITCH_HALF_WIDTH},
    {PITCH_HALF_LENGTH, PITCH_HALF_WIDTH},
    {0.0, PITCH_HALF_WIDTH},
};

static PyObject *str_x, *str_y, *str_vx, *str_vy, *str_body_deg, *str_stamina;
static PyObject *str_collided_ball, *str_collided_player, *str_collided_post;
static PyObject *str_recovery, *str_effort, *str_capacity, *str_catch_ban;

/* Attribute reads of hfo2d's slotted dataclasses (PlayerState, BallState: @dataclass(slots=True)) without the
 * generic attribute lookup: the offset of a plain object slot (a T_OBJECT_EX member descriptor) is cached per
 * (type, name), and an object of another type, or whose type resolves the name otherwise (a property, a
 * __getattr__ hook), takes PyObject_GetAttr. A new reference, or NULL with an exception set. */
#define SLOT_CACHE_SIZE 64
typedef struct {
    PyTypeObject *type; /* a strong reference, so that the type outlives its entry */
    PyObject *name;     /* interned */
    Py_ssize_t offset;  /* -1: the generic lookup */
} SlotEntry;
static SlotEntry slot_cache[SLOT_CACHE_SIZE];
static int slot_cache_len = 0;

static PyObject *
read_attr(PyObject *obj, PyObject *name)
{
    PyTypeObject *type = Py_TYPE(obj);
    for (int i = 0; i < slot_cache_len; i++) {
        SlotEntry *entry = &slot_cache[i];
        if (entry->type == type && entry->name == name) {
            if (entry->offset >= 0) {
                PyObject *value = *(PyObject **)((char *)obj + entry->offset);
                if (value != NULL) {
                    Py_INCREF(value);
                    return value;
                }
            }
            return PyObject_GetAttr(obj, name); /* an unset slot raises AttributeError there */
        }
    }
    if (slot_cache_len < SLOT_CACHE_SIZE && type->tp_getattro == PyObject_GenericGetAttr) {
        Py_ssize_t offset = -1;
        PyObject *descr = PyObject_GetAttr((PyObject *)type, name);
        if (descr == NULL) {
            PyErr_Clear();
        }
        else {
            if (Py_IS_TYPE(descr, &PyMemberDescr_Type)) {
                PyMemberDef *member = ((PyMemberDescrObject *)descr)->d_member;
                if (member->type == T_OBJECT_EX && !(member->flags & READ_RESTRICTED)) {
                    offset = member->offset;
                }
            }
            Py_DECREF(descr);
        }
        Py_INCREF(type);
        slot_cache[slot_cache_len].type = type;
        slot_cache[slot_cache_len].name = name;
        slot_cache[slot_cache_len].offset = offset;
        slot_cache_len++;
    }
    return PyObject_GetAttr(obj, name);
}

static int
get_double(PyObject *obj, PyObject *name, double *out)
{
    PyObject *value = read_attr(obj, name);
    if (value == NULL) {
        return -1;
    }
    double v = PyFloat_AsDouble(value);
    Py_DECREF(value);
    if (v == -1.0 && PyErr_Occurred()) {
        return -1;
    }
    *out = v;
    return 0;
}

static int
get_flag(PyObject *obj, PyObject *name, int *out)
{
    PyObject *value = read_attr(obj, name);
    if (value == NULL) {
        return -1;
    }
    int truth = PyObject_IsTrue(value);
    Py_DECREF(value);
    if (truth < 0) {
        return -1;
    }
    *out = truth;
    return 0;
}

/* Set an attribute (a new float or bool): by the cached slot offset as read_attr finds it, else PyObject_SetAttr.
 * Steals nothing: ``value`` stays the caller's. 0, or -1 with an exception set. */
static int
write_attr(PyObject *obj, PyObject *name, PyObject *value)
{
    PyTypeObject *type = Py_TYPE(obj);
    if (type->tp_setattro != PyObject_GenericSetAttr) { /* a frozen dataclass, a __setattr__ hook */
        return PyObject_SetAttr(obj, name, value);
    }
    for (int i = 0; i < slot_cache_len; i++) {
        SlotEntry *entry = &slot_cache[i];
        if (entry->type == type && entry->name == name) {
            if (entry->offset >= 0) {
                PyObject **slot = (PyObject **)((char *)obj + entry->offset);
                PyObject *old = *slot;
                Py_INCREF(value);
                *slot = value;
                Py_XDECREF(old);
                return 0;
            }
            break;
        }
    }
    return PyObject_SetAttr(obj, name, value);
}

static int
write_double(PyObject *obj, PyObject *name, double value)
{
    PyObject *number = PyFloat_FromDouble(value);
    if (number == NULL) {
        return -1;
    }
    int status = write_attr(obj, name, number);
    Py_DECREF(number);
    return status;
}

typedef struct {
    double x, y, vx, vy, body_deg;
} Other;

/* features.py's _append_player_block */
static int
player_block(double *out, const Other *other, double self_x, double self_y, double body_cos, double body_sin,
             double max_dist)
{
    double dx = other->x - self_x;
    double dy = other->y - self_y;
    double dist = py_hypot(dx, dy);
    if (dist < 0.0) {
        return -1;
    }
    double heading_cos = 1.0, heading_sin = 0.0; /* rcsc's Vector2D::th() of the zero vector is 0 */
    if (dist > 0.0) {
        heading_cos = dx / dist;
        heading_sin = dy / dist;
    }
    double other_body = other->body_deg * (M_PI / 180.0);
    double speed = py_hypot(other->vx, other->vy);
    if (speed < 0.0) {
        return -1;
    }
    double vel_cos = 1.0, vel_sin = 0.0;
    if (speed > 0.0) {
        vel_cos = other->vx / speed;
        vel_sin = other->vy / speed;
    }
    out[0] = heading_sin * body_cos - heading_cos * body_sin;
    out[1] = heading_cos * body_cos + heading_sin * body_sin;
    out[2] = dist < max_dist ? 1.0 - 2.0 / max_dist * dist : -1.0;
    out[3] = sin(other_body);
    out[4] = cos(other_body);
    out[5] = speed < PLAYER_SPEED_MAX ? 2.0 * speed / PLAYER_SPEED_MAX - 1.0 : 1.0;
    out[6] = vel_sin;
    out[7] = vel_cos;
    return 0;
}

/* One group (teammates or opponents): its blocks, nearest first, then the empty slots. Returns the number of
 * features written, or -1 with an exception set. */
static Py_ssize_t
group_blocks(double *out, PyObject *group, double x, double y, double body_cos, double body_sin, double max_dist)
{
    PyObject *seq = PySequence_Fast(group, "teammates and opponents must be sequences of players");
    if (seq == NULL) {
        return -1;
    }
    Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
    if (n > MAX_GROUP) {
        Py_DECREF(seq);
        PyErr_Format(PyExc_ValueError, "at most %d players per group, got %zd", MAX_GROUP, n);
        return -1;
    }
    Other others[MAX_GROUP];
    double keys[MAX_GROUP];
    int order[MAX_GROUP];
    PyObject **items = PySequence_Fast_ITEMS(seq);
    for (Py_ssize_t i = 0; i < n; i++) {
        Other *o = &others[i];
        if (get_double(items[i], str_x, &o->x) < 0 || get_double(items[i], str_y, &o->y) < 0 ||
            get_double(items[i], str_vx, &o->vx) < 0 || get_double(items[i], str_vy, &o->vy) < 0 ||
            get_double(items[i], str_body_deg, &o->body_deg) < 0) {
            Py_DECREF(seq);
            return -1;
        }
        /* sorted(group, key=lambda other: (other.x - x) ** 2 + (other.y - y) ** 2): Python's float ** calls
         * libm pow on the magnitude (the sign of a square is +) */
        keys[i] = pow(fabs(o->x - x), 2.0) + pow(fabs(o->y - y), 2.0);
        order[i] = (int)i;
    }
    Py_DECREF(seq);
    if (n > 1) { /* stable insertion sort by key, as Python's sorted */
        for (Py_ssize_t i = 1; i < n; i++) {
            int item = order[i];
            Py_ssize_t j = i;
            while (j > 0 && keys[item] < keys[order[j - 1]]) {
                order[j] = order[j - 1];
                j--;
            }
            order[j] = item;
        }
    }
    Py_ssize_t written = 0;
    for (Py_ssize_t i = 0; i < n; i++) {
        const Other *o = &others[order[i]];
        if (o->x > 0.0) { /* HFO lists a player only inside the HFO half (x > 0) */
            if (player_block(out + written, o, x, y, body_cos, body_sin, max_dist) < 0) {
                return -1;
            }
            written += FEATURES_PER_PLAYER;
        }
    }
    for (Py_ssize_t k = written; k < FEATURES_PER_PLAYER * n; k++) {
        out[k] = 0.0;
    }
    return FEATURES_PER_PLAYER * n;
}

static double
out_of_bounds(double d, double d_max)
{
    return d <= 0.0 ? 1.0 : (d >= d_max ? -1.0 : 1.0 - 2.0 * d / d_max);
}

static PyObject *
accel_low_level_feature_list(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 8 && nargs != 5) {
        PyErr_SetString(PyExc_TypeError,
                        "low_level_feature_list(player, ball, kickable_distance, teammates, opponents[, max_dist, "
                        "out_of_bounds_x_max, out_of_bounds_y_max])");
        return NULL;
    }
    PyObject *player = args[0], *ball = args[1], *teammates = args[3], *opponents = args[4];
    double kickable_distance;
    /* the paper era's normalisers unless given */
    double max_dist = MAX_HFO_DIST, oob_x_max = PITCH_HALF_LENGTH, oob_y_max = 2.0 * PITCH_HALF_WIDTH;
    if ((kickable_distance = PyFloat_AsDouble(args[2])) == -1.0 && PyErr_Occurred()) {
        return NULL;
    }
    if (nargs == 8) {
        max_dist = PyFloat_AsDouble(args[5]);
        oob_x_max = PyFloat_AsDouble(args[6]);
        oob_y_max = PyFloat_AsDouble(args[7]);
        if (PyErr_Occurred()) {
            return NULL;
        }
    }
    double x, y, vx, vy, body_deg, stamina, ball_x, ball_y, ball_vx, ball_vy;
    int collided_ball, collided_player, collided_post;
    if (get_double(player, str_x, &x) < 0 || get_double(player, str_y, &y) < 0 ||
        get_double(player, str_vx, &vx) < 0 || get_double(player, str_vy, &vy) < 0 ||
        get_double(player, str_body_deg, &body_deg) < 0 || get_double(player, str_stamina, &stamina) < 0 ||
        get_flag(player, str_collided_ball, &collided_ball) < 0 ||
        get_flag(player, str_collided_player, &collided_player) < 0 ||
        get_flag(player, str_collided_post, &collided_post) < 0 || get_double(ball, str_x, &ball_x) < 0 ||
        get_double(ball, str_y, &ball_y) < 0 || get_double(ball, str_vx, &ball_vx) < 0 ||
        get_double(ball, str_vy, &ball_vy) < 0) {
        return NULL;
    }
    Py_ssize_t n_mates = PyObject_Length(teammates);
    Py_ssize_t n_opps = PyObject_Length(opponents);
    if (n_mates < 0 || n_opps < 0) {
        return NULL;
    }
    if (n_mates > MAX_GROUP || n_opps > MAX_GROUP) {
        PyErr_Format(PyExc_ValueError, "at most %d players per group", MAX_GROUP);
        return NULL;
    }
    double f[NUM_BASIC_FEATURES + FEATURES_PER_PLAYER * 2 * MAX_GROUP];

    double body = body_deg * (M_PI / 180.0);
    double body_cos = cos(body);
    double body_sin = sin(body);
    double speed = py_hypot(vx, vy);
    if (speed < 0.0) {
        return NULL;
    }
    double vel_cos = 1.0, vel_sin = 0.0; /* heading of a zero velocity is 0 */
    if (speed > 0.0) {
        vel_cos = vx / speed;
        vel_sin = vy / speed;
    }
    f[0] = 1.0; /* self position valid (fullstate) */
    f[1] = 1.0; /* self velocity valid */
    f[2] = body_sin * vel_cos - body_cos * vel_sin;
    f[3] = body_cos * vel_cos + body_sin * vel_sin;
    f[4] = speed < SELF_SPEED_MAX ? 2.0 * speed / SELF_SPEED_MAX - 1.0 : 1.0;
    f[5] = body_sin;
    f[6] = body_cos;
    f[7] = stamina > 0.0 ? (stamina < STAMINA_MAX ? 2.0 * stamina / STAMINA_MAX - 1.0 : 1.0) : -1.0;
    f[8] = -1.0; /* frozen: nobody tackles */
    f[9] = collided_ball ? 1.0 : -1.0;
    f[10] = collided_player ? 1.0 : -1.0;
    f[11] = collided_post ? 1.0 : -1.0;

    /* the landmarks: (sin, cos) of bearing = heading - body expanded without atan2, then the proximity; the
     * Python's unrolled block forms each offset's products with cos and sin the same way */
    double two_over_max_dist = 2.0 / max_dist;
    for (int k = 0; k < 11; k++) {
        double dx = LANDMARKS[k][0] - x;
        double dy = LANDMARKS[k][1] - y;
        double d = py_hypot(dx, dy);
        if (d < 0.0) {
            return NULL;
        }
        double *t = f + 13 + 3 * k;
        if (d > 0.0) {
            t[0] = (dy * body_cos - dx * body_sin) / d;
            t[1] = (dx * body_cos + dy * body_sin) / d;
            t[2] = d < max_dist ? 1.0 - two_over_max_dist * d : -1.0;
        }
        else { /* rcsc's Vector2D::th() of the zero vector is 0, so the bearing is -body */
            t[0] = -body_sin;
            t[1] = body_cos;
            t[2] = 1.0;
        }
    }
    double dx = ball_x - x;
    double dy = ball_y - y;
    double dist = py_hypot(dx, dy);
    if (dist < 0.0) {
        return NULL;
    }
    double heading_cos = 1.0, heading_sin = 0.0;
    if (dist > 0.0) {
        heading_cos = dx / dist;
        heading_sin = dy / dist;
    }
    f[12] = dist <= kickable_distance ? 1.0 : -1.0;
    double ball_speed = py_hypot(ball_vx, ball_vy);
    if (ball_speed < 0.0) {
        return NULL;
    }
    double ball_vel_cos = 1.0, ball_vel_sin = 0.0;
    if (ball_speed > 0.0) {
        ball_vel_cos = ball_vx / ball_speed;
        ball_vel_sin = ball_vy / ball_speed;
    }
    f[46] = out_of_bounds(x, oob_x_max);
    f[47] = out_of_bounds(PITCH_HALF_LENGTH - x, oob_x_max);
    f[48] = out_of_bounds(PITCH_HALF_WIDTH + y, oob_y_max);
    f[49] = out_of_bounds(PITCH_HALF_WIDTH - y, oob_y_max);
    f[50] = 1.0; /* ball position valid */
    f[51] = heading_sin * body_cos - heading_cos * body_sin;
    f[52] = heading_cos * body_cos + heading_sin * body_sin;
    f[53] = dist < max_dist ? 1.0 - two_over_max_dist * dist : -1.0;
    f[54] = 1.0; /* ball velocity valid */
    f[55] = ball_speed < BALL_SPEED_MAX ? 2.0 * ball_speed / BALL_SPEED_MAX - 1.0 : 1.0;
    f[56] = ball_vel_sin;
    f[57] = ball_vel_cos;

    Py_ssize_t n = NUM_BASIC_FEATURES;
    Py_ssize_t written = group_blocks(f + n, teammates, x, y, body_cos, body_sin, max_dist);
    if (written < 0) {
        return NULL;
    }
    n += written;
    written = group_blocks(f + n, opponents, x, y, body_cos, body_sin, max_dist);
    if (written < 0) {
        return NULL;
    }
    n += written;
    PyObject *list = PyList_New(n);
    if (list == NULL) {
        return NULL;
    }
    for (Py_ssize_t i = 0; i < n; i++) {
        PyObject *value = PyFloat_FromDouble(f[i]);
        if (value == NULL) {
            Py_DECREF(list);
            return NULL;
        }
        PyList_SET_ITEM(list, i, value);
    }
    return list;
}

/* ------------------------------------------------------------------------------------------------------------
 * The other players' reach of the intercept table (port of hfo2d.agent2d.intercept._predict_player_python,
 * _opp_turns, cycles_to_reach_distance and fastest_reach_python): librcsc d222758 rcsc/player/player_intercept.cpp
 * PlayerIntercept::predict (predictTurnCycle with at most one turn, canReachAfterDash, predictFinal) and
 * rcsc/player/player_type.cpp PlayerType::cyclesToReachDistance, under fullstate (every count 0).
 * The server constants are bound by intercept._bind (bind_intercept), whenever hfo2d binds server parameters.
 * ------------------------------------------------------------------------------------------------------------ */
#define BALL_CACHE_MAX 101 /* the move sums go to 100; intercept_table.cpp MAX_CYCLE 30 gives at most 31 points */
#define DASH_TABLE_MAX 256

static int intercept_bound = 0;
static double kickable_area;  /* PlayerType::kickableArea */
static double real_speed_max; /* PlayerType::realSpeedMax */
static long tackle_cycles;    /* tackle_cycles */
static double player_move_sums[101]; /* intercept._PF: (1 - decay**n) / (1 - decay) */
static double dash_table[DASH_TABLE_MAX]; /* common.DASH_DISTANCE_TABLE */
static Py_ssize_t dash_table_len = 0;

static int
double_table(PyObject *values, double *out, Py_ssize_t max_len, Py_ssize_t *len, const char *what)
{
    PyObject *seq = PySequence_Fast(values, what);
    if (seq == NULL) {
        return -1;
    }
    Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
    if (n > max_len || (len == NULL && n != max_len)) {
        Py_DECREF(seq);
        PyErr_Format(PyExc_ValueError, "%s: %zd values, at most %zd", what, n, max_len);
        return -1;
    }
    for (Py_ssize_t i = 0; i < n; i++) {
        double v = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(seq, i));
        if (v == -1.0 && PyErr_Occurred()) {
            Py_DECREF(seq);
            return -1;
        }
        out[i] = v;
    }
    Py_DECREF(seq);
    if (len != NULL) {
        *len = n;
    }
    return 0;
}

static PyObject *
accel_bind_intercept(PyObject *module, PyObject *args)
{
    double area, speed;
    long cycles;
    PyObject *sums, *table;
    if (!PyArg_ParseTuple(args, "ddlOO:bind_intercept", &area, &speed, &cycles, &sums, &table)) {
        return NULL;
    }
    double new_sums[101], new_table[DASH_TABLE_MAX];
    Py_ssize_t new_len;
    if (double_table(sums, new_sums, 101, NULL, "player move sums (101)") < 0 ||
        double_table(table, new_table, DASH_TABLE_MAX, &new_len, "dash distance table") < 0) {
        return NULL;
    }
    if (new_len < 1) {
        PyErr_SetString(PyExc_ValueError, "the dash distance table is empty");
        return NULL;
    }
    /* nothing changes unless everything is valid */
    kickable_area = area;
    real_speed_max = speed;
    tackle_cycles = cycles;
    memcpy(player_move_sums, new_sums, sizeof new_sums);
    memcpy(dash_table, new_table, sizeof(double) * (size_t)new_len);
    dash_table_len = new_len;
    intercept_bound = 1;
    Py_RETURN_NONE;
}

/* AngleDeg::normalize (intercept._norm) */
static double
norm_deg(double a)
{
    if (a < -360.0 || a > 360.0) {
        a = fmod(a, 360.0);
    }
    if (a < -180.0) {
        a += 360.0;
    }
    if (a > 180.0) {
        a -= 360.0;
    }
    return a;
}

/* Vector2D::th().degree() (intercept._th); Python's math.atan2 equals libm's for finite arguments */
static double
th_deg(double x, double y)
{
    if (x == 0.0 && y == 0.0) {
        return 0.0;
    }
    double a = atan2(y, x) * (180.0 / M_PI);
    if (a > 180.0 || a < -180.0) {
        a = norm_deg(a);
    }
    return a;
}

/* PlayerType::cyclesToReachDistance (intercept.cycles_to_reach_distance: bisect_left on the dash table) */
static long
cycles_to_reach(double dist)
{
    if (dist <= 0.001) {
        return 0;
    }
    double target = dist - 0.001;
    Py_ssize_t lo = 0, hi = dash_table_len;
    while (lo < hi) {
        Py_ssize_t mid = (lo + hi) / 2;
        if (dash_table[mid] < target) {
            lo = mid + 1;
        }
        else {
            hi = mid;
        }
    }
    if (lo < dash_table_len) {
        return (long)lo + 1;
    }
    double more = ceil((dist - dash_table[dash_table_len - 1]) / real_speed_max);
    return (long)dash_table_len + (more < 1.0e9 ? (long)more : 1000000000L); /* (dist is finite) */
}

/* intercept._opp_turns: at most one turn, and the distance from the drift point after n cycles to the ball */
static int
opp_turns(double ox, double oy, double ux, double uy, double obody, int n, double xbx, double xby,
          double *target_dist)
{
    double f = player_move_sums[n];
    double zx = ox + ux * f;
    double zy = oy + uy * f;
    double tx = xbx - zx;
    double ty = xby - zy;
    double dist = sqrt(tx * tx + ty * ty);
    double margin = 180.0;
    if (dist > kickable_area) {
        double r = kickable_area / dist;
        margin = r >= 1.0 ? 90.0 : asin(r) * (180.0 / M_PI); /* AngleDeg::asin_deg (r > 0) */
    }
    if (margin < 12.0) { /* player_intercept.cpp: minimum turn margin 12 degrees */
        margin = 12.0;
    }
    double diff = fabs(norm_deg(th_deg(tx, ty) - obody));
    if (dist < 5.0 && diff > 90.0) { /* close: a back dash will do */
        diff = 180.0 - diff;
    }
    *target_dist = dist;
    return diff > margin ? 1 : 0;
}

/* The Python raises where it turns a float into an int (math.floor of an infinity or a NaN): so does the kernel,
 * before any work. */
static int
check_finite(double value, const char *what)
{
    if (isnan(value)) {
        PyErr_Format(PyExc_ValueError, "%s is a NaN (cannot convert float NaN to integer)", what);
        return -1;
    }
    if (isinf(value)) {
        PyErr_Format(PyExc_OverflowError, "%s is infinite (cannot convert float infinity to integer)", what);
        return -1;
    }
    return 0;
}

/* intercept._predict_player_python on a ball cache of n_cache points (xs, ys) */
static long
predict_player(double ox, double oy, double ux, double uy, double obody, long frozen, int resting_shortcut,
               double self_dist, const double *xs, const double *ys, Py_ssize_t n_cache, double rel_y)
{
    obody = norm_deg(obody);
    /* (rel_y is finite here, see check_finite; a bound past any ball cache stands for Python's larger ints) */
    double lower = floor(fabs(rel_y) / real_speed_max);
    long min_cycle = lower < 1.0e9 ? (long)lower : 1000000000L;
    /* librcsc PlayerObject::tackleCount from the remaining freeze (see the Python) */
    long tackle_extra = 0;
    if (frozen > 0) {
        long tackle_count = tackle_cycles - 1 - frozen;
        tackle_extra = tackle_cycles - tackle_count - 2;
        if (tackle_extra < 0) {
            tackle_extra = 0;
        }
        min_cycle += tackle_extra;
    }
    if (min_cycle < 0) {
        min_cycle = 0;
    }
    if (resting_shortcut && min_cycle < n_cache) {
        /* a resting ball: every cached point is one point, skip the cycles the reach bound fails at once */
        double dx = ox - xs[min_cycle], dy = oy - ys[min_cycle];
        double d = sqrt(dx * dx + dy * dy);
        while (min_cycle < n_cache && kickable_area + real_speed_max * (double)min_cycle + 0.5 < d) {
            min_cycle++;
        }
    }
    double target_dist;
    for (long cycle = min_cycle; cycle < n_cache; cycle++) {
        double dx = ox - xs[cycle], dy = oy - ys[cycle];
        if (kickable_area + real_speed_max * (double)cycle + 0.5 < sqrt(dx * dx + dy * dy)) {
            continue;
        }
        int n_turn = opp_turns(ox, oy, ux, uy, obody, (int)cycle, xs[cycle], ys[cycle], &target_dist);
        long n_dash = cycle - n_turn;
        if (n_dash < 0) {
            continue;
        }
        double dist = target_dist - kickable_area;
        if (dist < 0.0) {
            return cycle;
        }
        if (cycles_to_reach(dist) + tackle_extra <= n_dash) {
            return cycle;
        }
    }
    /* predictFinal: the ball's last cached point */
    int n_turn = opp_turns(ox, oy, ux, uy, obody, 100, xs[n_cache - 1], ys[n_cache - 1], &target_dist);
    double dash_dist = target_dist - kickable_area;
    dash_dist -= self_dist * 0.03; /* distFromSelf; 0 for a teammate */
    if (dash_dist < 0.0) {
        return (long)n_cache;
    }
    long n_dash = cycles_to_reach(dash_dist);
    if (n_dash < 1) {
        n_dash = 1;
    }
    return n_turn + n_dash > n_cache ? n_turn + n_dash : (long)n_cache;
}

/* ------------------------------------------------------------------------------------------------------------
 * predictFinal of the self intercept (port of hfo2d.agent2d.intercept._final_entry_python and _wait): librcsc
 * d222758 rcsc/player/self_intercept_v13.cpp SelfInterceptV13::predictFinal (predictTurnCycle inlined for cycle
 * 100) and rcsc/player/stamina_model.cpp StaminaModel::simulateWait / simulateDash at full power.
 * Constants bound by intercept._bind (bind_self_final), in the order of SELF_FINAL_NAMES.
 * ------------------------------------------------------------------------------------------------------------ */
enum {
    SF_PEN_LINE_X, SF_PEN_HALF_W, SF_CATCHABLE_AREA, SF_MIN_TURN_THR, SF_MAX_MOMENT, SF_INERTIA_MOMENT,
    SF_PLAYER_DECAY, SF_STAMINA_INC_MAX, SF_EFFORT_MAX, SF_MAX_POWER, SF_RECOVER_DEC_THR_VALUE, SF_STAMINA_MAX,
    SF_RECOVER_MIN, SF_RECOVER_DEC, SF_EFFORT_DEC_THR_VALUE, SF_EFFORT_MIN, SF_EFFORT_DEC, SF_EFFORT_INC_THR_VALUE,
    SF_EFFORT_INC, SF_CONTROL_AREA_BUF, SF_ONE_MINUS_PD, SF_DASH_POWER_RATE, SF_SAFE_STAMINA, SF_MIN_DASH_POWER,
    SF_COUNT
};
static double sf[SF_COUNT];
static double ball_move_sums[101]; /* intercept._BF: (1 - ball_decay**n) / (1 - ball_decay) */
static double player_decays[101]; /* intercept._PD: player_decay**n */
static double first_term_dens[101]; /* intercept._FT_DEN: 1 - player_decay**n */
static int self_final_bound = 0;

static PyObject *
accel_bind_self_final(PyObject *module, PyObject *args)
{
    PyObject *constants, *sums, *decays, *dens;
    if (!PyArg_ParseTuple(args, "OOOO:bind_self_final", &constants, &sums, &decays, &dens)) {
        return NULL;
    }
    double new_constants[SF_COUNT], new_sums[101], new_decays[101], new_dens[101];
    if (double_table(constants, new_constants, SF_COUNT, NULL, "self intercept constants") < 0 ||
        double_table(sums, new_sums, 101, NULL, "ball move sums (101)") < 0 ||
        double_table(decays, new_decays, 101, NULL, "player decays (101)") < 0 ||
        double_table(dens, new_dens, 101, NULL, "first term denominators (101)") < 0) {
        return NULL;
    }
    memcpy(sf, new_constants, sizeof sf);
    memcpy(ball_move_sums, new_sums, sizeof ball_move_sums);
    memcpy(player_decays, new_decays, sizeof player_decays);
    memcpy(first_term_dens, new_dens, sizeof first_term_dens);
    self_final_bound = 1;
    Py_RETURN_NONE;
}

/* intercept._wait: one cycle of stamina recovery (the capacity assumed ample) */
static void
stamina_wait(double *st, double *ef, double *rec)
{
    if (*st <= sf[SF_RECOVER_DEC_THR_VALUE] && *rec > sf[SF_RECOVER_MIN]) {
        *rec -= sf[SF_RECOVER_DEC];
        if (*rec < sf[SF_RECOVER_MIN]) {
            *rec = sf[SF_RECOVER_MIN];
        }
    }
    if (*st <= sf[SF_EFFORT_DEC_THR_VALUE]) {
        if (*ef > sf[SF_EFFORT_MIN]) {
            *ef -= sf[SF_EFFORT_DEC];
            if (*ef < sf[SF_EFFORT_MIN]) {
                *ef = sf[SF_EFFORT_MIN];
            }
        }
    }
    else if (*st >= sf[SF_EFFORT_INC_THR_VALUE] && *ef < sf[SF_EFFORT_MAX]) {
        *ef += sf[SF_EFFORT_INC];
        if (*ef > sf[SF_EFFORT_MAX]) {
            *ef = sf[SF_EFFORT_MAX];
        }
    }
    double inc = sf[SF_STAMINA_INC_MAX] * *rec;
    double room = sf[SF_STAMINA_MAX] - *st;
    *st += inc < room ? inc : room;
    if (*st > sf[SF_STAMINA_MAX]) {
        *st = sf[SF_STAMINA_MAX];
    }
}

static PyObject *
accel_final_entry(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 16) {
        PyErr_SetString(PyExc_TypeError, "final_entry(px, py, vx, vy, body, speed, lk, bx, by, wx, wy, stamina, "
                                         "effort, recovery, max_cycle, player_rand)");
        return NULL;
    }
    if (!self_final_bound || !intercept_bound) {
        PyErr_SetString(PyExc_RuntimeError, "hfo2d._accel: bind_self_final / bind_intercept were never called");
        return NULL;
    }
    double a[16];
    for (int i = 0; i < 16; i++) {
        if (i == 6 || i == 14) {
            continue;
        }
        a[i] = PyFloat_AsDouble(args[i]);
    }
    int lk = PyObject_IsTrue(args[6]);
    long max_cycle = PyLong_AsLong(args[14]);
    if (PyErr_Occurred() || lk < 0) {
        return NULL;
    }
    double px = a[0], py = a[1], vx = a[2], vy = a[3], body = a[4], speed = a[5];
    double bx = a[7], by = a[8], wx = a[9], wy = a[10], player_rand = a[15];
    double f = player_move_sums[100];
    double qx = px + vx * f;
    double qy = py + vy * f;
    double g = ball_move_sums[100];
    double xfx = bx + wx * g;
    double xfy = by + wy * g;
    int goalie_mode = lk && xfx < sf[SF_PEN_LINE_X] && fabs(xfy) < sf[SF_PEN_HALF_W];
    double ca = goalie_mode ? sf[SF_CATCHABLE_AREA] - 0.15 : kickable_area;
    /* predictTurnCycle for cycle 100 */
    double tx = xfx - qx;
    double ty = xfy - qy;
    double target_angle = th_deg(tx, ty);
    double diff = fabs(norm_deg(target_angle - body));
    double target_dist = sqrt(tx * tx + ty * ty);
    double margin = 180.0;
    double control_buf = ca - 0.25 > 0.5 ? ca - 0.25 : 0.5; /* max(0.5, ca - 0.25) */
    if (control_buf < target_dist) {
        double r = control_buf / target_dist; /* AngleDeg::asin_deg */
        margin = r >= 1.0 ? 90.0 : (r <= -1.0 ? -90.0 : asin(r) * (180.0 / M_PI));
    }
    if (margin < sf[SF_MIN_TURN_THR]) {
        margin = sf[SF_MIN_TURN_THR];
    }
    long n_turn = 0;
    if (diff > margin) {
        double max_moment = sf[SF_MAX_MOMENT] * (1.0 - player_rand);
        double s = speed;
        while (diff > margin) {
            diff -= max_moment / (1.0 + sf[SF_INERTIA_MOMENT] * s);
            s *= sf[SF_PLAYER_DECAY];
            n_turn++;
        }
    }
    long n_dash = cycles_to_reach(target_dist - ca);
    if (max_cycle > n_turn + n_dash) {
        n_dash = max_cycle - n_turn;
    }
    double st = a[11], ef = a[12], rec = a[13];
    for (long k = 0; k < n_turn; k++) { /* _waited(wt, n_turn) */
        stamina_wait(&st, &ef, &rec);
    }
    double inc = sf[SF_STAMINA_INC_MAX] * rec;
    long n_dash_left;
    if (ef >= sf[SF_EFFORT_MAX] && st - sf[SF_MAX_POWER] * (double)n_dash > sf[SF_RECOVER_DEC_THR_VALUE]) {
        if (st == floor(st) && inc == floor(inc)) { /* float.is_integer() of finite numbers */
            st -= (sf[SF_MAX_POWER] - inc) * (double)n_dash;
        }
        else {
            for (long k = 0; k < n_dash; k++) {
                st = st - sf[SF_MAX_POWER] + inc;
            }
        }
        n_dash_left = 0;
    }
    else {
        n_dash_left = n_dash;
    }
    for (long k = 0; k < n_dash_left; k++) {
        st -= sf[SF_MAX_POWER];
        if (st > sf[SF_RECOVER_DEC_THR_VALUE] && ef >= sf[SF_EFFORT_MAX]) {
            double room = sf[SF_STAMINA_MAX] - st;
            st += inc < room ? inc : room;
            if (st > sf[SF_STAMINA_MAX]) {
                st = sf[SF_STAMINA_MAX];
            }
        }
        else {
            if (st < 0.0) {
                st = 0.0;
            }
            stamina_wait(&st, &ef, &rec);
            inc = sf[SF_STAMINA_INC_MAX] * rec;
        }
    }
    return Py_BuildValue("(llddd)", n_turn, n_dash, xfx, xfy, st);
}

/* ball_part(bx, by, wx, wy, self_kickable, resting_shortcuts, ball_decay, x_max, y_max, max_cycle)
 *   -> (cache, resting, sin_a, cos_a): port of hfo2d.agent2d.intercept._ball_part_python, librcsc d222758
 * rcsc/player/intercept_table.cpp InterceptTable::createBallCache (the ball's path under its decay, at most
 * max_cycle steps, stopped after 5 steps once slower than 0.01 or off the area) and the frame along the ball's
 * velocity (sin and cos of -angle(W)). */
static PyObject *
accel_ball_part(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 10) {
        PyErr_SetString(PyExc_TypeError, "ball_part(bx, by, wx, wy, self_kickable, resting_shortcuts, ball_decay, "
                                         "x_max, y_max, max_cycle)");
        return NULL;
    }
    double bx = PyFloat_AsDouble(args[0]);
    double by = PyFloat_AsDouble(args[1]);
    double wx = PyFloat_AsDouble(args[2]);
    double wy = PyFloat_AsDouble(args[3]);
    double decay = PyFloat_AsDouble(args[6]);
    double x_max = PyFloat_AsDouble(args[7]);
    double y_max = PyFloat_AsDouble(args[8]);
    long max_cycle = PyLong_AsLong(args[9]);
    if (PyErr_Occurred()) {
        return NULL;
    }
    int self_kickable = PyObject_IsTrue(args[4]);
    int shortcuts = PyObject_IsTrue(args[5]);
    if (self_kickable < 0 || shortcuts < 0) {
        return NULL;
    }
    int resting = wx == 0.0 && wy == 0.0 && shortcuts;
    double sin_a = -0.0, cos_a = 1.0; /* a resting ball: angle 0, rotated by -0.0 */
    if (!resting) {
        double a = -th_deg(wx, wy) * (M_PI / 180.0);
        sin_a = sin(a);
        cos_a = cos(a);
    }
    PyObject *cache = PyList_New(0);
    if (cache == NULL) {
        return NULL;
    }
    PyObject *point = Py_BuildValue("(dd)", bx, by);
    if (point == NULL || PyList_Append(cache, point) < 0) {
        Py_XDECREF(point);
        Py_DECREF(cache);
        return NULL;
    }
    Py_DECREF(point);
    if (self_kickable) {
        /* createBallCache stops at the current position */
    }
    else if (resting) {
        /* every step adds +-0: the first step's point repeats (one tuple, as the Python appends it) */
        double x = bx + wx, y = by + wy;
        point = Py_BuildValue("(dd)", x, y);
        if (point == NULL) {
            Py_DECREF(cache);
            return NULL;
        }
        int copies = !(fabs(x) > x_max || fabs(y) > y_max) ? 5 : 1;
        for (int k = 0; k < copies; k++) {
            if (PyList_Append(cache, point) < 0) {
                Py_DECREF(point);
                Py_DECREF(cache);
                return NULL;
            }
        }
        Py_DECREF(point);
    }
    else {
        double x = bx, y = by, vx = wx, vy = wy;
        for (long i = 1; i <= max_cycle; i++) {
            x += vx;
            y += vy;
            vx *= decay;
            vy *= decay;
            point = Py_BuildValue("(dd)", x, y);
            if (point == NULL || PyList_Append(cache, point) < 0) {
                Py_XDECREF(point);
                Py_DECREF(cache);
                return NULL;
            }
            Py_DECREF(point);
            if (i >= 5 && vx * vx + vy * vy < 0.01 * 0.01) {
                break;
            }
            if (fabs(x) > x_max || fabs(y) > y_max) {
                break;
            }
        }
    }
    return Py_BuildValue("(NOdd)", cache, resting ? Py_True : Py_False, sin_a, cos_a);
}

/* ------------------------------------------------------------------------------------------------------------
 * The short steps of the self intercept (port of hfo2d.agent2d.intercept._turn_short_python and
 * _dash_short_python): librcsc d222758 rcsc/player/self_intercept_v13.cpp SelfInterceptV13::predictTurnCycleShort
 * (full max moment, no player_rand) and predictDashCycleShort (the waiting candidate, then the dashes after the
 * turns with simulateDash's stamina inlined).
 * ------------------------------------------------------------------------------------------------------------ */
static double
asin_deg(double x) /* AngleDeg::asin_deg (intercept._asin_deg) */
{
    if (x >= 1.0) {
        return 90.0;
    }
    if (x <= -1.0) {
        return -90.0;
    }
    return asin(x) * (180.0 / M_PI);
}

/* turn_short(target_angle, target_dist, body_angle, speed, turn_area) -> (n_turn, dash_angle) */
static PyObject *
accel_turn_short(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 5) {
        PyErr_SetString(PyExc_TypeError, "turn_short(target_angle, target_dist, body_angle, speed, turn_area)");
        return NULL;
    }
    if (!self_final_bound) {
        PyErr_SetString(PyExc_RuntimeError, "hfo2d._accel: bind_self_final was never called");
        return NULL;
    }
    double target_angle = PyFloat_AsDouble(args[0]);
    double target_dist = PyFloat_AsDouble(args[1]);
    double body_angle = PyFloat_AsDouble(args[2]);
    double speed = PyFloat_AsDouble(args[3]);
    double turn_area = PyFloat_AsDouble(args[4]);
    if (PyErr_Occurred()) {
        return NULL;
    }
    double signed_diff = norm_deg(target_angle - body_angle);
    double diff = fabs(signed_diff);
    double margin = 180.0;
    if (turn_area < target_dist) {
        margin = asin_deg(turn_area / target_dist);
        if (margin < sf[SF_MIN_TURN_THR]) {
            margin = sf[SF_MIN_TURN_THR];
        }
    }
    if (diff <= margin) {
        return Py_BuildValue("(id)", 0, body_angle);
    }
    long n_turn = 0;
    double s = speed;
    while (diff > margin) {
        diff -= sf[SF_MAX_MOMENT] / (1.0 + sf[SF_INERTIA_MOMENT] * s);
        s *= sf[SF_PLAYER_DECAY];
        n_turn++;
    }
    if (diff < 0.0) {
        diff = 0.0;
    }
    double angle = signed_diff > 0.0 ? norm_deg(target_angle - diff) : norm_deg(target_angle + diff);
    return Py_BuildValue("(ld)", n_turn, angle);
}

#define MODE_NORMAL 0  /* hfo2d.agent2d.common.NORMAL */
#define MODE_EXHAUST 1 /* hfo2d.agent2d.common.EXHAUST */

/* dash_short(px, py, vx, vy, stamina, effort, recovery, cycle, n_turn, dash_angle, back, xbx, xby, ca, ix, iy,
 * target_angle) -> list of the 0 to 2 candidates (mode, n_turn, n_dash, first_power, 0.0, x, y, ball_dist,
 * stamina); (stamina, effort, recovery) is the state before any wait (the Python's wt[0]). */
static PyObject *
accel_dash_short(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 17) {
        PyErr_SetString(PyExc_TypeError, "dash_short(px, py, vx, vy, stamina, effort, recovery, cycle, n_turn, "
                                         "dash_angle, back, xbx, xby, ca, ix, iy, target_angle)");
        return NULL;
    }
    if (!self_final_bound) {
        PyErr_SetString(PyExc_RuntimeError, "hfo2d._accel: bind_self_final was never called");
        return NULL;
    }
    double a[17];
    for (int i = 0; i < 17; i++) {
        if (i == 7 || i == 8 || i == 10) {
            continue;
        }
        a[i] = PyFloat_AsDouble(args[i]);
    }
    long cycle = PyLong_AsLong(args[7]);
    long n_turn = PyLong_AsLong(args[8]);
    int back = PyObject_IsTrue(args[10]);
    if (PyErr_Occurred() || back < 0) {
        return NULL;
    }
    if (cycle < 0 || cycle > 100 || n_turn < 0 || n_turn > 100) {
        PyErr_Format(PyExc_ValueError, "cycle %ld and n_turn %ld must lie in 0..100", cycle, n_turn);
        return NULL;
    }
    double px = a[0], py = a[1], vx = a[2], vy = a[3], st0 = a[4], ef0 = a[5], rec0 = a[6];
    double dash_angle = a[9], xbx = a[11], xby = a[12], ca = a[13], ix = a[14], iy = a[15];
    double target_angle = a[16];
    PyObject *candidates = PyList_New(0);
    if (candidates == NULL) {
        return NULL;
    }
    long max_dash = cycle - n_turn;
    double ctrl2 = (ca - sf[SF_CONTROL_AREA_BUF]) * (ca - sf[SF_CONTROL_AREA_BUF]);
    double d2 = (ix - xbx) * (ix - xbx) + (iy - xby) * (iy - xby);
    if (d2 < ctrl2) {
        double st = st0, ef = ef0, rec = rec0;
        for (long k = 0; k < cycle; k++) { /* _waited(wt, cycle) */
            stamina_wait(&st, &ef, &rec);
        }
        PyObject *entry = Py_BuildValue("(illdddddd)", MODE_NORMAL, n_turn, max_dash, 0.0, 0.0, ix, iy, sqrt(d2),
                                        st);
        if (entry == NULL || PyList_Append(candidates, entry) < 0) {
            Py_XDECREF(entry);
            Py_DECREF(candidates);
            return NULL;
        }
        Py_DECREF(entry);
    }
    if (fabs(norm_deg(target_angle - dash_angle)) > 90.0) {
        return candidates;
    }
    double st = st0, ef = ef0, rec = rec0;
    for (long k = 0; k < n_turn; k++) { /* _waited(wt, n_turn) */
        stamina_wait(&st, &ef, &rec);
    }
    double g = player_move_sums[n_turn];
    double mx = px + vx * g;
    double my = py + vy * g;
    double d = player_decays[n_turn];
    double mvx = vx * d;
    double mvy = vy * d;
    double ux = cos(dash_angle * (M_PI / 180.0));
    double uy = sin(dash_angle * (M_PI / 180.0));
    double rc = cos(-dash_angle * (M_PI / 180.0));
    double rs = sin(-dash_angle * (M_PI / 180.0));
    double first_power = 0.0;
    for (long n_dash = 1; n_dash <= max_dash; n_dash++) {
        double first_speed = ((xbx - mx) * rc - (xby - my) * rs) * sf[SF_ONE_MINUS_PD] /
                             first_term_dens[max_dash - n_dash + 1];
        double rate = ef * sf[SF_DASH_POWER_RATE];
        double power = (first_speed - (mvx * rc - mvy * rs)) / rate;
        double avail = st - sf[SF_SAFE_STAMINA];
        if (avail < 0.0) {
            avail = 0.0;
        }
        if (back) {
            power = -power;
            if (power < sf[SF_MIN_DASH_POWER]) {
                power = sf[SF_MIN_DASH_POWER];
            }
            else if (power > 0.0) {
                power = 0.0;
            }
            if (power < avail * -0.5) {
                power = avail * -0.5;
            }
            st -= power * -2.0;
        }
        else {
            if (power < 0.0) {
                power = 0.0;
            }
            else if (power > sf[SF_MAX_POWER]) {
                power = sf[SF_MAX_POWER];
            }
            if (avail < power) {
                power = avail;
            }
            st -= power;
        }
        if (n_dash == 1) {
            first_power = power;
        }
        double acc = fabs(power * rate);
        mvx += ux * acc;
        mvy += uy * acc;
        mx += mvx;
        my += mvy;
        mvx *= sf[SF_PLAYER_DECAY];
        mvy *= sf[SF_PLAYER_DECAY];
        if (st < 0.0) { /* simulateDash (the payment is above) */
            st = 0.0;
        }
        if (st > sf[SF_RECOVER_DEC_THR_VALUE] && ef >= sf[SF_EFFORT_MAX]) {
            double inc = sf[SF_STAMINA_INC_MAX] * rec;
            double room = sf[SF_STAMINA_MAX] - st;
            st += inc < room ? inc : room;
            if (st > sf[SF_STAMINA_MAX]) {
                st = sf[SF_STAMINA_MAX];
            }
        }
        else {
            stamina_wait(&st, &ef, &rec);
        }
    }
    d2 = (mx - xbx) * (mx - xbx) + (my - xby) * (my - xby);
    if (d2 < ctrl2 ||
        (px - mx) * (px - mx) + (py - my) * (py - my) > (px - xbx) * (px - xbx) + (py - xby) * (py - xby)) {
        int mode = st < sf[SF_RECOVER_DEC_THR_VALUE] ? MODE_EXHAUST : MODE_NORMAL;
        PyObject *entry = Py_BuildValue("(illdddddd)", mode, n_turn, max_dash, first_power, 0.0, mx, my, sqrt(d2),
                                        st);
        if (entry == NULL || PyList_Append(candidates, entry) < 0) {
            Py_XDECREF(entry);
            Py_DECREF(candidates);
            return NULL;
        }
        Py_DECREF(entry);
    }
    return candidates;
}

/* a ball cache (a sequence of (x, y)) as two arrays; the number of points, or -1 with an exception set */
static Py_ssize_t
read_ball_cache(PyObject *cache, double *xs, double *ys)
{
    if (!intercept_bound) {
        PyErr_SetString(PyExc_RuntimeError, "hfo2d._accel: bind_intercept was never called");
        return -1;
    }
    PyObject *seq = PySequence_Fast(cache, "the ball cache must be a sequence of (x, y)");
    if (seq == NULL) {
        return -1;
    }
    Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
    if (n < 1 || n > BALL_CACHE_MAX) {
        Py_DECREF(seq);
        PyErr_Format(PyExc_ValueError, "the ball cache holds %zd points, not 1..%d", n, BALL_CACHE_MAX);
        return -1;
    }
    for (Py_ssize_t i = 0; i < n; i++) {
        PyObject *point = PySequence_Fast_GET_ITEM(seq, i);
        if (!PyTuple_Check(point) || PyTuple_GET_SIZE(point) != 2) {
            Py_DECREF(seq);
            PyErr_SetString(PyExc_TypeError, "a ball cache point must be a tuple (x, y)");
            return -1;
        }
        xs[i] = PyFloat_AsDouble(PyTuple_GET_ITEM(point, 0));
        ys[i] = PyFloat_AsDouble(PyTuple_GET_ITEM(point, 1));
        if (PyErr_Occurred()) {
            Py_DECREF(seq);
            return -1;
        }
    }
    Py_DECREF(seq);
    return n;
}

static PyObject *
accel_predict_player(PyObject *module, PyObject *args)
{
    double ox, oy, ux, uy, obody, self_dist, rel_y;
    long frozen;
    int resting_shortcut;
    PyObject *cache;
    if (!PyArg_ParseTuple(args, "dddddlpdOd:predict_player", &ox, &oy, &ux, &uy, &obody, &frozen,
                          &resting_shortcut, &self_dist, &cache, &rel_y)) {
        return NULL;
    }
    double xs[BALL_CACHE_MAX], ys[BALL_CACHE_MAX];
    Py_ssize_t n = read_ball_cache(cache, xs, ys);
    if (n < 0 || check_finite(rel_y, "rel_y") < 0) {
        return NULL;
    }
    return PyLong_FromLong(predict_player(ox, oy, ux, uy, obody, frozen, resting_shortcut, self_dist, xs, ys, n,
                                          rel_y));
}

static PyObject *
accel_fastest_reach(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 11) {
        PyErr_SetString(PyExc_TypeError, "fastest_reach(players, cache, bx, by, px, py, resting_shortcut, sin_a, "
                                         "cos_a, teammate, best)");
        return NULL;
    }
    double v[6];
    for (int i = 0; i < 4; i++) {
        v[i] = PyFloat_AsDouble(args[2 + i]);
    }
    double sin_a = PyFloat_AsDouble(args[7]);
    double cos_a = PyFloat_AsDouble(args[8]);
    long best = PyLong_AsLong(args[10]);
    if (PyErr_Occurred()) {
        return NULL;
    }
    int resting_shortcut = PyObject_IsTrue(args[6]);
    int teammate = PyObject_IsTrue(args[9]);
    if (resting_shortcut < 0 || teammate < 0) {
        return NULL;
    }
    double bx = v[0], by = v[1], px = v[2], py = v[3];
    double xs[BALL_CACHE_MAX], ys[BALL_CACHE_MAX];
    Py_ssize_t n = read_ball_cache(args[1], xs, ys);
    if (n < 0) {
        return NULL;
    }
    PyObject *seq = PySequence_Fast(args[0], "players must be a sequence of (x, y, vx, vy, body, frozen)");
    if (seq == NULL) {
        return NULL;
    }
    for (Py_ssize_t i = 0; i < PySequence_Fast_GET_SIZE(seq); i++) {
        PyObject *player = PySequence_Fast_GET_ITEM(seq, i);
        if (!PyTuple_Check(player) || PyTuple_GET_SIZE(player) != 6) {
            Py_DECREF(seq);
            PyErr_SetString(PyExc_TypeError, "a player must be a tuple (x, y, vx, vy, body, frozen)");
            return NULL;
        }
        for (int k = 0; k < 5; k++) {
            v[k] = PyFloat_AsDouble(PyTuple_GET_ITEM(player, k));
        }
        long frozen = PyLong_AsLong(PyTuple_GET_ITEM(player, 5));
        if (PyErr_Occurred()) {
            Py_DECREF(seq);
            return NULL;
        }
        double x = v[0], y = v[1];
        double rel_y = (x - bx) * sin_a + (y - by) * cos_a;
        if (check_finite(rel_y, "a player's offset from the ball's line") < 0) {
            Py_DECREF(seq);
            return NULL;
        }
        double self_dist = teammate ? 0.0 : sqrt((x - px) * (x - px) + (y - py) * (y - py));
        long reach = predict_player(x, y, v[2], v[3], v[4], frozen, resting_shortcut, self_dist, xs, ys, n, rel_y);
        if (reach < best) {
            best = reach;
        }
    }
    Py_DECREF(seq);
    return PyLong_FromLong(best);
}

static PyObject *
accel_cycles_to_reach_distance(PyObject *module, PyObject *arg)
{
    double dist = PyFloat_AsDouble(arg);
    if (dist == -1.0 && PyErr_Occurred()) {
        return NULL;
    }
    if (!intercept_bound) {
        PyErr_SetString(PyExc_RuntimeError, "hfo2d._accel: bind_intercept was never called");
        return NULL;
    }
    if (isinf(dist) && dist > 0.0) { /* the Python's int(ceil(inf)) (a NaN reads 1 in both) */
        return PyErr_Format(PyExc_OverflowError, "the distance is infinite (cannot convert float infinity to "
                                                 "integer)"), NULL;
    }
    return PyLong_FromLong(cycles_to_reach(dist));
}

/* ------------------------------------------------------------------------------------------------------------
 * The NPCs' per-cycle conversions of the other players (port of hfo2d.agent2d.goalie.mirrored_players_python):
 * librcsc d222758 rcsc/player/fullstate_sensor.cpp (parse, then reverse for the right side: positions and
 * velocities negated, body normalize(body + 180)) and the distances world_model.cpp sorts its player lists by.
 * ------------------------------------------------------------------------------------------------------------ */
static PyObject *str_tackle_cycles;

/* mirrored_self(me, ball) -> (px, py, vx, vy, body, stamina, effort, recovery, bx, by, wx, wy): the deciding
 * right-side player's own numbers and the ball's as its client reads them (port of the conversions at the start
 * of Agent2dGoalie._view and Agent2dDefender._view, goalie.mirrored_self_python) */
static PyObject *
accel_mirrored_self(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 2) {
        PyErr_SetString(PyExc_TypeError, "mirrored_self(me, ball)");
        return NULL;
    }
    PyObject *me = args[0], *ball = args[1];
    PyObject *const names[12] = {str_x,       str_y,      str_vx,       str_vy, str_body_deg, str_stamina,
                                 str_effort,  str_recovery, str_x,      str_y,  str_vx,       str_vy};
    double v[12];
    for (int k = 0; k < 12; k++) {
        double raw;
        if (get_double(k < 8 ? me : ball, names[k], &raw) < 0 || fullstate_number(raw, &v[k]) < 0) {
            return NULL;
        }
    }
    return Py_BuildValue("(dddddddddddd)", -v[0], -v[1], -v[2], -v[3], norm_deg(v[4] + 180.0), v[5], v[6], v[7],
                         -v[8], -v[9], -v[10], -v[11]);
}

static PyObject *
accel_mirrored_players(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 6) {
        PyErr_SetString(PyExc_TypeError, "mirrored_players(players, skip, bx, by, px, py)");
        return NULL;
    }
    PyObject *skip = args[1];
    double bx = PyFloat_AsDouble(args[2]);
    double by = PyFloat_AsDouble(args[3]);
    double px = PyFloat_AsDouble(args[4]);
    double py = PyFloat_AsDouble(args[5]);
    if (PyErr_Occurred()) {
        return NULL;
    }
    PyObject *seq = PySequence_Fast(args[0], "players must be a sequence of PlayerState");
    if (seq == NULL) {
        return NULL;
    }
    Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
    PyObject *result = PyList_New(0);
    if (result == NULL) {
        Py_DECREF(seq);
        return NULL;
    }
    for (Py_ssize_t i = 0; i < n; i++) {
        PyObject *player = PySequence_Fast_GET_ITEM(seq, i);
        if (player == skip) {
            continue;
        }
        double raw[5], v[5];
        if (get_double(player, str_x, &raw[0]) < 0 || get_double(player, str_y, &raw[1]) < 0 ||
            get_double(player, str_vx, &raw[2]) < 0 || get_double(player, str_vy, &raw[3]) < 0 ||
            get_double(player, str_body_deg, &raw[4]) < 0) {
            goto fail;
        }
        for (int k = 0; k < 5; k++) {
            if (fullstate_number(raw[k], &v[k]) < 0) {
                goto fail;
            }
        }
        PyObject *frozen_obj = read_attr(player, str_tackle_cycles);
        if (frozen_obj == NULL) {
            goto fail;
        }
        PyObject *frozen = PyNumber_Long(frozen_obj); /* int(p.tackle_cycles) */
        Py_DECREF(frozen_obj);
        if (frozen == NULL) {
            goto fail;
        }
        double x = -v[0], y = -v[1];
        double ball_dist = py_hypot(x - bx, y - by);
        double self_dist = ball_dist < 0.0 ? -1.0 : py_hypot(x - px, y - py);
        if (self_dist < 0.0) {
            Py_DECREF(frozen);
            goto fail;
        }
        PyObject *other = Py_BuildValue("(dddddN)", x, y, -v[2], -v[3], norm_deg(v[4] + 180.0), frozen);
        if (other == NULL) {
            goto fail;
        }
        PyObject *entry = Py_BuildValue("(ddNO)", ball_dist, self_dist, other, player);
        if (entry == NULL || PyList_Append(result, entry) < 0) {
            Py_XDECREF(entry);
            goto fail;
        }
        Py_DECREF(entry);
    }
    Py_DECREF(seq);
    return result;
fail:
    Py_DECREF(seq);
    Py_DECREF(result);
    return NULL;
}

/* ------------------------------------------------------------------------------------------------------------
 * One object's move (port of hfo2d.physics.World._move_python): rcssserver 82212ee object.cpp MPObject::_inc
 * (accelerate with the caps, the velocity noise, move, decay). The goal-post rule stays in Python
 * (World._posts, pymunk): near a post the kernel returns the velocity and lets Python finish the move.
 * ------------------------------------------------------------------------------------------------------------ */
static PyObject *str_ax, *str_ay;

/* move_object(obj, size, decay, rand, speed_max, accel_max, uniforms, next_uniform, post_x, post_y, post_radius)
 *   -> None: the buffer holds fewer than two unused uniforms and a draw is needed; nothing was changed (refill,
 *      then call again);
 *   -> int: the move is done (obj updated), the next unused uniform's index;
 *   -> (vx, vy, next_uniform): the object may reach a post; obj is unchanged and Python applies the post rule
 *      to obj.x, obj.y and this velocity (before decay), then clears the acceleration. */
static PyObject *
accel_move_object(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 11) {
        PyErr_SetString(PyExc_TypeError, "move_object(obj, size, decay, rand, speed_max, accel_max, uniforms, "
                                         "next_uniform, post_x, post_y, post_radius)");
        return NULL;
    }
    PyObject *obj = args[0], *uniforms = args[6];
    double size = PyFloat_AsDouble(args[1]);
    double decay = PyFloat_AsDouble(args[2]);
    double rand = PyFloat_AsDouble(args[3]);
    double speed_max = PyFloat_AsDouble(args[4]);
    double accel_max = PyFloat_AsDouble(args[5]);
    Py_ssize_t i = PyLong_AsSsize_t(args[7]);
    double post_x = PyFloat_AsDouble(args[8]);
    double post_y = PyFloat_AsDouble(args[9]);
    double post_radius = PyFloat_AsDouble(args[10]);
    if (PyErr_Occurred()) {
        return NULL;
    }
    if (!PyList_Check(uniforms)) {
        PyErr_SetString(PyExc_TypeError, "uniforms must be a list of floats");
        return NULL;
    }
    double vx, vy, ax, ay, x, y;
    if (get_double(obj, str_vx, &vx) < 0 || get_double(obj, str_vy, &vy) < 0 || get_double(obj, str_ax, &ax) < 0 ||
        get_double(obj, str_ay, &ay) < 0 || get_double(obj, str_x, &x) < 0 || get_double(obj, str_y, &y) < 0) {
        return NULL;
    }
    if (ax != 0.0 || ay != 0.0) {
        double a = py_hypot(ax, ay);
        if (a < 0.0) {
            return NULL;
        }
        if (a > accel_max) {
            ax *= accel_max / a;
            ay *= accel_max / a;
        }
        vx += ax;
        vy += ay;
        double v = py_hypot(vx, vy);
        if (v < 0.0) {
            return NULL;
        }
        if (v > speed_max) {
            vx *= speed_max / v;
            vy *= speed_max / v;
        }
    }
    if (rand > 0.0 && (vx != 0.0 || vy != 0.0)) {
        if (i + 2 > PyList_GET_SIZE(uniforms)) {
            Py_RETURN_NONE; /* Python draws the next block from the world's generator first */
        }
        double u0 = PyFloat_AsDouble(PyList_GET_ITEM(uniforms, i));
        double u1 = PyFloat_AsDouble(PyList_GET_ITEM(uniforms, i + 1));
        if (PyErr_Occurred()) {
            return NULL;
        }
        i += 2;
        double speed = py_hypot(vx, vy);
        if (speed < 0.0) {
            return NULL;
        }
        double r = rand * speed * u0;
        double th = M_PI * (2.0 * u1 - 1.0);
        vx += r * cos(th);
        vy += r * sin(th);
    }
    double reach = size + post_radius + fabs(vx) + fabs(vy);
    if (fabs(fabs(x) - post_x) < reach && fabs(fabs(y) - post_y) < reach) {
        return Py_BuildValue("(ddn)", vx, vy, i);
    }
    if (write_attr(obj, str_collided_post, Py_False) < 0 || write_double(obj, str_x, x + vx) < 0 ||
        write_double(obj, str_y, y + vy) < 0 || write_double(obj, str_vx, vx * decay) < 0 ||
        write_double(obj, str_vy, vy * decay) < 0 || write_double(obj, str_ax, 0.0) < 0 ||
        write_double(obj, str_ay, 0.0) < 0) {
        return NULL;
    }
    return PyLong_FromSsize_t(i);
}

/* ------------------------------------------------------------------------------------------------------------
 * The end of a server cycle for every player (port of hfo2d.physics._update_stamina_python): rcssserver 82212ee
 * player.cpp Player::updateStamina (hfo_reference §4.5) and Player::updateCapacity's catch ban; and the first-pass
 * overlap test of World._collisions (port of hfo2d.physics._any_overlap_python).
 * ------------------------------------------------------------------------------------------------------------ */
static PyObject *int_zero, *int_one; /* the Python ints 0 and 1 */

/* update_stamina(players, recover_dec_thr, effort_dec_thr, effort_inc_thr, stamina_max, recover_min, recover_dec,
 * effort_min, effort_dec, effort_init, effort_inc, stamina_inc_max, limited_capacity) */
static PyObject *
accel_update_stamina(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 13) {
        PyErr_SetString(PyExc_TypeError, "update_stamina(players, recover_dec_thr, effort_dec_thr, effort_inc_thr, "
                                         "stamina_max, recover_min, recover_dec, effort_min, effort_dec, "
                                         "effort_init, effort_inc, stamina_inc_max, limited_capacity)");
        return NULL;
    }
    double c[11];
    for (int k = 0; k < 11; k++) {
        c[k] = PyFloat_AsDouble(args[1 + k]);
    }
    int limited_capacity = PyObject_IsTrue(args[12]);
    if (PyErr_Occurred() || limited_capacity < 0) {
        return NULL;
    }
    double recover_dec_thr = c[0], effort_dec_thr = c[1], effort_inc_thr = c[2], smax = c[3];
    double recover_min = c[4], recover_dec = c[5], effort_min = c[6], effort_dec = c[7], effort_init = c[8];
    double effort_inc = c[9], stamina_inc_max = c[10];
    PyObject *seq = PySequence_Fast(args[0], "players must be a sequence of PlayerState");
    if (seq == NULL) {
        return NULL;
    }
    for (Py_ssize_t i = 0; i < PySequence_Fast_GET_SIZE(seq); i++) {
        PyObject *player = PySequence_Fast_GET_ITEM(seq, i);
        double stamina, recovery, effort;
        if (get_double(player, str_stamina, &stamina) < 0 || get_double(player, str_recovery, &recovery) < 0) {
            goto fail;
        }
        /* thresholds on the current stamina, then recover; max(a, b) / min(a, b) as the builtins pick */
        if (stamina <= recover_dec_thr && recovery > recover_min) {
            double lowered = recovery - recover_dec;
            recovery = lowered > recover_min ? lowered : recover_min;
            if (write_double(player, str_recovery, recovery) < 0) {
                goto fail;
            }
        }
        if (get_double(player, str_effort, &effort) < 0) {
            goto fail;
        }
        if (stamina <= effort_dec_thr && effort > effort_min) {
            double lowered = effort - effort_dec;
            effort = lowered > effort_min ? lowered : effort_min;
            if (write_double(player, str_effort, effort) < 0) {
                goto fail;
            }
        }
        if (stamina >= effort_inc_thr && effort < effort_init) {
            double raised = effort + effort_inc;
            effort = raised < effort_init ? raised : effort_init;
            if (write_double(player, str_effort, effort) < 0) {
                goto fail;
            }
        }
        double inc = stamina_inc_max * recovery;
        double room = smax - stamina;
        if (room < inc) {
            inc = room;
        }
        if (limited_capacity) {
            double capacity;
            if (get_double(player, str_capacity, &capacity) < 0) {
                goto fail;
            }
            if (capacity >= inc) {
                if (write_double(player, str_capacity, capacity - inc) < 0) {
                    goto fail;
                }
            }
            else {
                inc = capacity;
                if (write_double(player, str_capacity, 0.0) < 0) {
                    goto fail;
                }
            }
        }
        stamina += inc > 0.0 ? inc : 0.0;
        if (write_double(player, str_stamina, stamina < smax ? stamina : smax) < 0) {
            goto fail;
        }
        PyObject *ban = read_attr(player, str_catch_ban);
        if (ban == NULL) {
            goto fail;
        }
        int positive = PyObject_RichCompareBool(ban, int_zero, Py_GT);
        if (positive > 0) {
            PyObject *lowered = PyNumber_Subtract(ban, int_one);
            if (lowered == NULL || write_attr(player, str_catch_ban, lowered) < 0) {
                Py_XDECREF(lowered);
                Py_DECREF(ban);
                goto fail;
            }
            Py_DECREF(lowered);
        }
        Py_DECREF(ban);
        if (positive < 0) {
            goto fail;
        }
    }
    Py_DECREF(seq);
    Py_RETURN_NONE;
fail:
    Py_DECREF(seq);
    return NULL;
}

/* any_overlap(players, ball, bp_limit2, pp_limit2) -> bool */
static PyObject *
accel_any_overlap(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 4) {
        PyErr_SetString(PyExc_TypeError, "any_overlap(players, ball, bp_limit2, pp_limit2)");
        return NULL;
    }
    double bp_limit2 = PyFloat_AsDouble(args[2]);
    double pp_limit2 = PyFloat_AsDouble(args[3]);
    double bx, by;
    if (PyErr_Occurred() || get_double(args[1], str_x, &bx) < 0 || get_double(args[1], str_y, &by) < 0) {
        return NULL;
    }
    PyObject *seq = PySequence_Fast(args[0], "players must be a sequence of PlayerState");
    if (seq == NULL) {
        return NULL;
    }
    Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
    if (n > 2 * MAX_GROUP) {
        Py_DECREF(seq);
        PyErr_Format(PyExc_ValueError, "at most %d players", 2 * MAX_GROUP);
        return NULL;
    }
    double xs[2 * MAX_GROUP], ys[2 * MAX_GROUP];
    for (Py_ssize_t i = 0; i < n; i++) {
        PyObject *player = PySequence_Fast_GET_ITEM(seq, i);
        if (get_double(player, str_x, &xs[i]) < 0 || get_double(player, str_y, &ys[i]) < 0) {
            Py_DECREF(seq);
            return NULL;
        }
    }
    Py_DECREF(seq);
    for (Py_ssize_t i = 0; i < n; i++) {
        double dx = xs[i] - bx, dy = ys[i] - by;
        if (dx * dx + dy * dy < bp_limit2) {
            Py_RETURN_TRUE;
        }
    }
    for (Py_ssize_t i = 0; i + 1 < n; i++) {
        for (Py_ssize_t j = i + 1; j < n; j++) {
            double dx = xs[j] - xs[i], dy = ys[j] - ys[i];
            if (dx * dx + dy * dy < pp_limit2) {
                Py_RETURN_TRUE;
            }
        }
    }
    Py_RETURN_FALSE;
}

/* ------------------------------------------------------------------------------------------------------------
 * A learning agent's flat action (port of the usual case of hfo2d.team.TeamGame._parse_action: a float32 or
 * float64 vector of the layout's length, every element in [0, 1]): HybridActionLayout.decode, the largest
 * preference (the first on ties) and its parameters mapped from [0, 1] onto their bounds.
 * ------------------------------------------------------------------------------------------------------------ */
#define FLAT_ACTION_MAX 64

/* decode_flat(action, size, decoding) -> (kind, parameters), or None where the Python must look (another type,
 * dtype, byte order or shape; a value outside [0, 1] or NaN: the Python raises its ValueError) */
static PyObject *
accel_decode_flat(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    if (nargs != 3) {
        PyErr_SetString(PyExc_TypeError, "decode_flat(action, size, decoding)");
        return NULL;
    }
    Py_ssize_t size = PyLong_AsSsize_t(args[1]);
    if (size == -1 && PyErr_Occurred()) {
        return NULL;
    }
    PyObject *decoding = args[2];
    if (!PyTuple_Check(decoding) || size < 1 || size > FLAT_ACTION_MAX || !PyObject_CheckBuffer(args[0])) {
        Py_RETURN_NONE;
    }
    Py_buffer view;
    if (PyObject_GetBuffer(args[0], &view, PyBUF_RECORDS_RO) < 0) {
        PyErr_Clear();
        Py_RETURN_NONE;
    }
    double values[FLAT_ACTION_MAX];
    int ok = view.ndim == 1 && view.shape[0] == size && view.format != NULL;
    int is_float = ok && (strcmp(view.format, "f") == 0 || strcmp(view.format, "<f") == 0 ||
                          strcmp(view.format, "=f") == 0);
    int is_double = ok && (strcmp(view.format, "d") == 0 || strcmp(view.format, "<d") == 0 ||
                           strcmp(view.format, "=d") == 0);
#if PY_BIG_ENDIAN
    is_float = ok && (strcmp(view.format, "f") == 0 || strcmp(view.format, "=f") == 0);
    is_double = ok && (strcmp(view.format, "d") == 0 || strcmp(view.format, "=d") == 0);
#endif
    if (is_float || is_double) {
        for (Py_ssize_t i = 0; i < size; i++) {
            const char *item = (const char *)view.buf + i * view.strides[0];
            double value;
            if (is_float) {
                float single;
                memcpy(&single, item, sizeof single);
                value = (double)single; /* exact, as ndarray.tolist() */
            }
            else {
                memcpy(&value, item, sizeof value);
            }
            if (!(0.0 <= value && value <= 1.0)) { /* (also a NaN) */
                ok = 0;
                break;
            }
            values[i] = value;
        }
    }
    else {
        ok = 0;
    }
    PyBuffer_Release(&view);
    Py_ssize_t kinds = PyTuple_GET_SIZE(decoding);
    if (!ok || kinds < 1 || kinds > size) {
        Py_RETURN_NONE;
    }
    Py_ssize_t kind = 0;
    for (Py_ssize_t index = 1; index < kinds; index++) {
        if (values[index] > values[kind]) {
            kind = index;
        }
    }
    PyObject *entry = PyTuple_GET_ITEM(decoding, kind); /* (start, ((low, high), ...)) */
    if (!PyTuple_Check(entry) || PyTuple_GET_SIZE(entry) != 2 || !PyTuple_Check(PyTuple_GET_ITEM(entry, 1))) {
        Py_RETURN_NONE;
    }
    Py_ssize_t start = PyLong_AsSsize_t(PyTuple_GET_ITEM(entry, 0));
    if (start == -1 && PyErr_Occurred()) {
        return NULL;
    }
    PyObject *bounds = PyTuple_GET_ITEM(entry, 1);
    Py_ssize_t n_parameters = PyTuple_GET_SIZE(bounds);
    if (start < 0 || start + n_parameters > size) {
        Py_RETURN_NONE;
    }
    PyObject *parameters = PyList_New(n_parameters);
    if (parameters == NULL) {
        return NULL;
    }
    for (Py_ssize_t k = 0; k < n_parameters; k++) {
        PyObject *pair = PyTuple_GET_ITEM(bounds, k);
        double low, high;
        if (!PyTuple_Check(pair) || PyTuple_GET_SIZE(pair) != 2) {
            Py_DECREF(parameters);
            Py_RETURN_NONE;
        }
        low = PyFloat_AsDouble(PyTuple_GET_ITEM(pair, 0));
        high = PyFloat_AsDouble(PyTuple_GET_ITEM(pair, 1));
        if (PyErr_Occurred()) {
            Py_DECREF(parameters);
            return NULL;
        }
        PyObject *value = PyFloat_FromDouble(low + (high - low) * values[start + k]);
        if (value == NULL) {
            Py_DECREF(parameters);
            return NULL;
        }
        PyList_SET_ITEM(parameters, k, value);
    }
    return Py_BuildValue("(nN)", kind, parameters);
}

/* ------------------------------------------------------------------------------------------------------------ */

static PyMethodDef accel_methods[] = {
    {"decode_flat", (PyCFunction)(void (*)(void))accel_decode_flat, METH_FASTCALL,
     "decode_flat(action, size, decoding) -> (kind, parameters) | None (see hfo2d.team.TeamGame._parse_action)."},
    {"turn_short", (PyCFunction)(void (*)(void))accel_turn_short, METH_FASTCALL,
     "turn_short(target_angle, target_dist, body_angle, speed, turn_area) -> (n_turn, dash_angle) (see "
     "hfo2d.agent2d.intercept._turn_short_python)."},
    {"dash_short", (PyCFunction)(void (*)(void))accel_dash_short, METH_FASTCALL,
     "dash_short(px, py, vx, vy, stamina, effort, recovery, cycle, n_turn, dash_angle, back, xbx, xby, ca, ix, iy, "
     "target_angle) -> list of candidates (see hfo2d.agent2d.intercept._dash_short_python)."},
    {"ball_part", (PyCFunction)(void (*)(void))accel_ball_part, METH_FASTCALL,
     "ball_part(bx, by, wx, wy, self_kickable, resting_shortcuts, ball_decay, x_max, y_max, max_cycle) -> (cache, "
     "resting, sin_a, cos_a) (see hfo2d.agent2d.intercept._ball_part_python)."},
    {"mirrored_self", (PyCFunction)(void (*)(void))accel_mirrored_self, METH_FASTCALL,
     "mirrored_self(me, ball) -> (px, py, vx, vy, body, stamina, effort, recovery, bx, by, wx, wy) (see "
     "hfo2d.agent2d.goalie.mirrored_self_python)."},
    {"update_stamina", (PyCFunction)(void (*)(void))accel_update_stamina, METH_FASTCALL,
     "update_stamina(players, ...) (see hfo2d.physics._update_stamina_python)."},
    {"any_overlap", (PyCFunction)(void (*)(void))accel_any_overlap, METH_FASTCALL,
     "any_overlap(players, ball, bp_limit2, pp_limit2) -> bool (see hfo2d.physics._any_overlap_python)."},
    {"move_object", (PyCFunction)(void (*)(void))accel_move_object, METH_FASTCALL,
     "move_object(obj, size, decay, rand, speed_max, accel_max, uniforms, next_uniform, post_x, post_y, "
     "post_radius) -> None | int | (vx, vy, next_uniform) (see hfo2d.physics.World._move)."},
    {"hypot", (PyCFunction)(void (*)(void))accel_hypot, METH_FASTCALL,
     "hypot(x, y) -> float: math.hypot(x, y), as the kernels compute it (NATIVE_HYPOT says how)."},
    {"mirrored_players", (PyCFunction)(void (*)(void))accel_mirrored_players, METH_FASTCALL,
     "mirrored_players(players, skip, bx, by, px, py) -> list of (ball distance, self distance, (x, y, vx, vy, "
     "body, frozen), player) in server order (see hfo2d.agent2d.goalie.mirrored_players_python)."},
    {"bind_intercept", accel_bind_intercept, METH_VARARGS,
     "bind_intercept(kickable_area, real_speed_max, tackle_cycles, player_move_sums, dash_distance_table): the "
     "server constants of the reach kernels (called by hfo2d.agent2d.intercept's binder)."},
    {"bind_self_final", accel_bind_self_final, METH_VARARGS,
     "bind_self_final(constants, ball_move_sums, player_decays, first_term_dens): the constants of the self "
     "intercept kernels, in hfo2d.agent2d.intercept._SELF_FINAL_NAMES order (called by intercept's binder)."},
    {"final_entry", (PyCFunction)(void (*)(void))accel_final_entry, METH_FASTCALL,
     "final_entry(px, py, vx, vy, body, speed, lk, bx, by, wx, wy, stamina, effort, recovery, max_cycle, "
     "player_rand) -> (turn_cycle, dash_cycle, self_x, self_y, stamina) (see "
     "hfo2d.agent2d.intercept._final_entry_python)."},
    {"predict_player", accel_predict_player, METH_VARARGS,
     "predict_player(ox, oy, ux, uy, obody, frozen, resting_shortcut, self_dist, cache, rel_y) -> int (see "
     "hfo2d.agent2d.intercept._predict_player_python)."},
    {"fastest_reach", (PyCFunction)(void (*)(void))accel_fastest_reach, METH_FASTCALL,
     "fastest_reach(players, cache, bx, by, px, py, resting_shortcut, sin_a, cos_a, teammate, best) -> int (see "
     "hfo2d.agent2d.intercept.fastest_reach_python)."},
    {"cycles_to_reach_distance", accel_cycles_to_reach_distance, METH_O,
     "cycles_to_reach_distance(dist) -> int (see hfo2d.agent2d.intercept.cycles_to_reach_distance)."},
    {"fullstate_value", accel_fullstate_value, METH_O,
     "fullstate_value(x) -> float: x printed with 6 significant digits and parsed back (see "
     "hfo2d.agent2d.goalie.fullstate_value)."},
    {"low_level_feature_list", (PyCFunction)(void (*)(void))accel_low_level_feature_list, METH_FASTCALL,
     "low_level_feature_list(player, ball, kickable_distance, teammates, opponents[, max_dist, "
     "out_of_bounds_x_max, out_of_bounds_y_max]) -> list[float] (see hfo2d.features.low_level_feature_list)."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef accel_module = {
    PyModuleDef_HEAD_INIT, "hfo2d._accel",
    "Optional compiled kernels of hfo2d (see envs/hfo2d/_accel.c); the pure-Python code is the reference.", -1,
    accel_methods,
};

#define INTERN(var, text)                                                                                     \
    if ((var = PyUnicode_InternFromString(text)) == NULL) {                                                   \
        return NULL;                                                                                          \
    }

PyMODINIT_FUNC
PyInit__accel(void)
{
    for (int k = 0; k < 23; k++) {
        pow10_exact[k] = k == 0 ? 1.0 : pow10_exact[k - 1] * 10.0; /* exact up to 10**22 */
    }
    MAX_HFO_DIST = sqrt(PITCH_HALF_LENGTH * PITCH_HALF_LENGTH + PITCH_HALF_WIDTH * PITCH_HALF_WIDTH);
    for (int k = 0; k < 309; k++) { /* correctly rounded, as float(10**k) */
        char text[16];
        snprintf(text, sizeof text, "1e%d", k);
        pow10_nearest[k] = PyOS_string_to_double(text, NULL, NULL);
        if (pow10_nearest[k] == -1.0 && PyErr_Occurred()) {
            return NULL;
        }
    }
    INTERN(str_x, "x");
    INTERN(str_y, "y");
    INTERN(str_vx, "vx");
    INTERN(str_vy, "vy");
    INTERN(str_body_deg, "body_deg");
    INTERN(str_stamina, "stamina");
    INTERN(str_collided_ball, "collided_ball");
    INTERN(str_collided_player, "collided_player");
    INTERN(str_collided_post, "collided_post");
    INTERN(str_tackle_cycles, "tackle_cycles");
    INTERN(str_ax, "ax");
    INTERN(str_recovery, "recovery");
    INTERN(str_effort, "effort");
    INTERN(str_capacity, "capacity");
    INTERN(str_catch_ban, "catch_ban");
    if ((int_zero = PyLong_FromLong(0)) == NULL || (int_one = PyLong_FromLong(1)) == NULL) {
        return NULL;
    }
    INTERN(str_ay, "ay");
    PyObject *math = PyImport_ImportModule("math");
    if (math == NULL) {
        return NULL;
    }
    math_hypot = PyObject_GetAttrString(math, "hypot");
    Py_DECREF(math);
    if (math_hypot == NULL) {
        return NULL;
    }
    PyObject *module = PyModule_Create(&accel_module);
    if (module == NULL) {
        return NULL;
    }
    PyObject *constants = Py_BuildValue(
        "{s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:i,s:i,s:d,s:d,s:d}", "PITCH_HALF_LENGTH", PITCH_HALF_LENGTH,
        "PITCH_HALF_WIDTH", PITCH_HALF_WIDTH, "GOAL_HALF_WIDTH", GOAL_HALF_WIDTH, "PENALTY_AREA_X", PENALTY_AREA_X,
        "PENALTY_AREA_HALF_WIDTH", PENALTY_AREA_HALF_WIDTH, "SELF_SPEED_MAX", SELF_SPEED_MAX, "PLAYER_SPEED_MAX",
        PLAYER_SPEED_MAX, "BALL_SPEED_MAX", BALL_SPEED_MAX, "STAMINA_MAX", STAMINA_MAX, "NUM_BASIC_FEATURES",
        NUM_BASIC_FEATURES, "FEATURES_PER_PLAYER", FEATURES_PER_PLAYER, "MAX_HFO_DIST", MAX_HFO_DIST,
        "OUT_OF_BOUNDS_X_DIST_MAX", PITCH_HALF_LENGTH, "OUT_OF_BOUNDS_Y_DIST_MAX", 2.0 * PITCH_HALF_WIDTH);
    if (PyModule_AddIntConstant(module, "NATIVE_HYPOT", NATIVE_HYPOT) < 0) {
        Py_XDECREF(constants);
        Py_DECREF(module);
        return NULL;
    }
    if (constants == NULL || PyModule_AddObject(module, "FEATURE_CONSTANTS", constants) < 0) {
        Py_XDECREF(constants);
        Py_DECREF(module);
        return NULL;
    }
    return module;
}
