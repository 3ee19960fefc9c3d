/* An outside controller for the monorail and the ship roll damper, written from the published documents only:
 * docs/protocol.md (channels, frame layout, handshake, lockstep, resends, end of run, authentication),
 * docs/transport.md (key file), docs/scenes.md (the scene keys, their defaults and units),
 * docs/models/monorail.md#firmware-law and docs/models/ship-roll-damper.md#firmware-laws (the laws and their
 * arithmetic, the cosine of docs/models/README.md#firmware-cosine).
 * It uses the C bindings that `lcm-gen -c` makes of the device's .lcm types, liblcm and libsodium: no header
 * and no library of the project. Compiled as C11 with -ffp-contract=off (no fused multiply-add), so that its
 * commands are the firmware's bit for bit.
 *
 *   interop_controller SCENE.toml [--key-file FILE] [--lcm-url URL] [--channel-suffix S] [--id N]
 *                                 [--timeout-ms MS] [--start-timeout-ms MS] [--lose-every N]
 * --lose-every N (testing): every N-th new answer is counted as sent (its freshness used) but not published, so
 * the plant sends the sensor frame again and this controller answers it again by the resend rule.
 *
 * Exit codes: 0 the plant ended the run and it was acknowledged; 2 refused before running (scene, key, options);
 * 3 transport failure; 6 the plant was lost. */
#define _POSIX_C_SOURCE 200809L

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include <lcm/lcm.h>
#include <sodium.h>

#include "gyrostab_msg_monorail_actuator_t.h"
#include "gyrostab_msg_monorail_sensor_t.h"
#include "gyrostab_msg_ship_roll_damper_actuator_t.h"
#include "gyrostab_msg_ship_roll_damper_sensor_t.h"
#include "outside_cos.h"

/* ---------------------------------------------------------------------------------------------------------
 * Scene file: the subset of TOML the shipped scenes use ([section], key = number | "string" | true/false, #
 * comments). Only the keys the controller needs are looked up; everything else is the plant's business. */

#define MAX_KEYS 256
typedef struct {
  char section[64];
  char key[64];
  char value[128];
} scene_entry_t;

typedef struct {
  scene_entry_t e[MAX_KEYS];
  int n;
  uint64_t hash; /* FNV-1a 64 of the file's bytes (docs/protocol.md, "Scene hash") */
} scene_t;

static char* trim(char* s) {
  while (*s && isspace((unsigned char)*s)) ++s;
  char* end = s + strlen(s);
  while (end > s && isspace((unsigned char)end[-1])) --end;
  *end = '\0';
  return s;
}

static int read_scene(const char* path, scene_t* sc) {
  FILE* f = fopen(path, "rb");
  if (!f) {
    fprintf(stderr, "interop_controller: cannot open %s: %s\n", path, strerror(errno));
    return 0;
  }
  static char text[1 << 20];
  const size_t len = fread(text, 1, sizeof text - 1, f);
  fclose(f);
  text[len] = '\0';
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < len; ++i) {
    h ^= (unsigned char)text[i];
    h *= 0x100000001b3ull;
  }
  sc->hash = h;
  sc->n = 0;
  char section[64] = "";
  char* save = NULL;
  for (char* line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
    int in_string = 0;
    for (char* p = line; *p; ++p) { /* cut the comment, not a '#' inside a string */
      if (*p == '"') in_string = !in_string;
      if (*p == '#' && !in_string) {
        *p = '\0';
        break;
      }
    }
    char* s = trim(line);
    if (*s == '\0') continue;
    if (*s == '[') {
      char* close = strchr(s, ']');
      if (!close) continue;
      *close = '\0';
      snprintf(section, sizeof section, "%s", trim(s + 1));
      continue;
    }
    char* eq = strchr(s, '=');
    if (!eq || sc->n == MAX_KEYS) continue;
    *eq = '\0';
    scene_entry_t* e = &sc->e[sc->n++];
    snprintf(e->section, sizeof e->section, "%s", section);
    snprintf(e->key, sizeof e->key, "%s", trim(s));
    char* v = trim(eq + 1);
    if (*v == '"') {
      ++v;
      char* q = strchr(v, '"');
      if (q) *q = '\0';
    }
    snprintf(e->value, sizeof e->value, "%s", v);
  }
  return 1;
}

static const char* scene_text(const scene_t* sc, const char* section, const char* key) {
  for (int i = 0; i < sc->n; ++i) {
    if (strcmp(sc->e[i].section, section) == 0 && strcmp(sc->e[i].key, key) == 0) return sc->e[i].value;
  }
  return NULL;
}

/* A number key, or its documented default (docs/scenes.md). strtod rounds correctly, as the plant's reader. */
static double scene_number(const scene_t* sc, const char* section, const char* key, double fallback) {
  const char* v = scene_text(sc, section, key);
  return v ? strtod(v, NULL) : fallback;
}

/* ---------------------------------------------------------------------------------------------------------
 * The laws (docs/models/monorail.md#firmware-law, docs/models/ship-roll-damper.md#firmware-laws). */

#define BIT_AXIS2_SATURATED (1u << 21)
#define BIT_BEYOND_SOFT_LIMIT (1u << 22)
#define BIT_END_STOP_BRAKING (1u << 23)
#define BIT_NON_FINITE_COMMAND (1u << 27)

typedef struct {
  double value;
  int clipped;
} clipped_t;

static clipped_t clip(double x, double limit) {
  if (x > limit) return (clipped_t){limit, 1};
  if (x < -limit) return (clipped_t){-limit, 1};
  return (clipped_t){x, 0};
}

typedef struct {
  double k, d, limit;
} monorail_law_t;

typedef struct {
  int active;
  double d2;                                                 /* passive */
  double B, H, k_r, d_c, k_c, beta_soft, w, k_s, a_b, delta_min, limit; /* active */
  int braking_direction;
} ship_law_t;

static double pos(double x) { return x > 0.0 ? x : 0.0; }

/* values: the sensor frame's signals in table order; cmd: the commands. Returns the law's status bits. */
static uint32_t monorail_step(const monorail_law_t* p, const double* in, double* cmd) {
  const double phi = in[0], beta_rate = in[3];
  const clipped_t m = clip(p->k * phi - p->d * beta_rate, p->limit);
  cmd[0] = m.value;
  cmd[1] = 0.0;
  return m.clipped ? BIT_AXIS2_SATURATED : 0u;
}

static uint32_t ship_step(ship_law_t* p, const double* in, double* cmd) {
  const double roll_rate = in[1], beta = in[2], beta_rate = in[3];
  uint32_t status = 0;
  cmd[1] = 0.0;
  if (!p->active) {
    const clipped_t m = clip(-p->d2 * beta_rate, p->limit);
    cmd[0] = m.value;
    return m.clipped ? BIT_AXIS2_SATURATED : 0u;
  }
  const double cb = outside_cos(beta);
  const double drive = p->H * cb * roll_rate;
  const double feedback = p->k_r * cb * roll_rate;
  const double sigma = beta < 0.0 ? -1.0 : 1.0;
  const double abs_beta = sigma * beta;
  const double dz = pos(abs_beta - p->beta_soft);
  const double g_raw = (p->beta_soft - abs_beta) / p->w;
  const double g = g_raw >= 1.0 ? 1.0 : pos(g_raw);
  if (dz > 0.0) status |= BIT_BEYOND_SOFT_LIMIT;
  const double law = feedback - p->d_c * beta_rate - p->k_c * beta - sigma * p->k_s * dz -
                     sigma * (1.0 - g) * (pos(sigma * feedback) + pos(sigma * drive));
  double torque = law;
  const double s = beta_rate > 0.0 ? 1.0 : (beta_rate < 0.0 ? -1.0 : 0.0);
  const int dir = (int)s;
  if (dir == 0 || p->braking_direction != dir) p->braking_direction = 0;
  if (dir != 0) {
    const double v = s * beta_rate;
    const double distance = p->beta_soft - s * beta;
    const double a_req = v * v / (2.0 * (distance > p->delta_min ? distance : p->delta_min));
    if (p->braking_direction == dir || a_req >= p->a_b) {
      p->braking_direction = dir;
      const double a_cmd = a_req > p->a_b ? a_req : p->a_b;
      const double brake = -s * (p->B * a_cmd + pos(s * drive));
      if ((s > 0.0 && brake < torque) || (s < 0.0 && brake > torque)) torque = brake;
      status |= BIT_END_STOP_BRAKING;
    }
  }
  const clipped_t m = clip(torque, p->limit);
  cmd[0] = m.value;
  if (m.clipped) status |= BIT_AXIS2_SATURATED;
  return status;
}

/* ---------------------------------------------------------------------------------------------------------
 * Frames: one generic view of both devices' types (docs/protocol.md, "The frame"). */

#define MAX_VALUES 8
typedef struct {
  int64_t tick, time_ns, third; /* third: sample_time_ns (sensor) or sensor_tick (actuator) */
  int32_t sequence, status;
  double v[MAX_VALUES];
  int64_t sim_time_us, scene, sender, session, freshness, mac;
} frame_t;

typedef enum { DEV_MONORAIL, DEV_SHIP } device_t;

#define SENSOR_VALUES 5
#define COMMAND_VALUES 2

static int decode_sensor(device_t dev, const void* buf, int len, frame_t* f) {
  if (len != 88 + 8 * SENSOR_VALUES) return 0;
#define COPY_HEADER(m)                                                                                    \
  f->tick = m.tick;                                                                                       \
  f->time_ns = m.time_ns;                                                                                 \
  f->third = m.sample_time_ns;                                                                            \
  f->sequence = m.sequence;                                                                               \
  f->status = m.status;                                                                                   \
  f->sim_time_us = m.sim_time_us;                                                                         \
  f->scene = m.scene;                                                                                     \
  f->sender = m.sender;                                                                                   \
  f->session = m.session;                                                                                 \
  f->freshness = m.freshness;                                                                             \
  f->mac = m.mac
  if (dev == DEV_MONORAIL) {
    gyrostab_msg_monorail_sensor_t m;
    if (gyrostab_msg_monorail_sensor_t_decode(buf, 0, len, &m) != len) return 0;
    COPY_HEADER(m);
    f->v[0] = m.tilt_rad;
    f->v[1] = m.tilt_rate_rad_s;
    f->v[2] = m.case_angle_rad;
    f->v[3] = m.case_rate_rad_s;
    f->v[4] = m.case_encoder_count;
  } else {
    gyrostab_msg_ship_roll_damper_sensor_t m;
    if (gyrostab_msg_ship_roll_damper_sensor_t_decode(buf, 0, len, &m) != len) return 0;
    COPY_HEADER(m);
    f->v[0] = m.roll_rad;
    f->v[1] = m.roll_rate_rad_s;
    f->v[2] = m.precession_angle_rad;
    f->v[3] = m.precession_rate_rad_s;
    f->v[4] = m.precession_encoder_count;
  }
#undef COPY_HEADER
  return 1;
}

static int encode_actuator(device_t dev, const frame_t* f, uint8_t* buf, int maxlen) {
#define FILL_HEADER(m)                                                                                    \
  m.tick = f->tick;                                                                                       \
  m.time_ns = f->time_ns;                                                                                 \
  m.sensor_tick = f->third;                                                                               \
  m.sequence = f->sequence;                                                                               \
  m.status = f->status;                                                                                   \
  m.sim_time_us = f->sim_time_us;                                                                         \
  m.scene = f->scene;                                                                                     \
  m.sender = f->sender;                                                                                   \
  m.session = f->session;                                                                                 \
  m.freshness = f->freshness;                                                                             \
  m.mac = f->mac
  if (dev == DEV_MONORAIL) {
    gyrostab_msg_monorail_actuator_t m;
    FILL_HEADER(m);
    m.motor_torque_Nm = f->v[0];
    m.precession_brake = f->v[1];
    return gyrostab_msg_monorail_actuator_t_encode(buf, 0, maxlen, &m);
  }
  gyrostab_msg_ship_roll_damper_actuator_t m;
  FILL_HEADER(m);
  m.precession_torque_Nm = f->v[0];
  m.precession_brake = f->v[1];
  return gyrostab_msg_ship_roll_damper_actuator_t_encode(buf, 0, maxlen, &m);
#undef FILL_HEADER
}

/* ---------------------------------------------------------------------------------------------------------
 * Authentication (docs/protocol.md, "Authentication"). */

#define DATA_ID_SENSOR 0x53454E53u
#define DATA_ID_ACTUATOR 0x41435455u

static void put_le(uint8_t* p, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) p[i] = (uint8_t)(v >> (8 * i));
}

/* The tag of an encoded frame of n values: SipHash-2-4 over data id, session, freshness and bytes [0, 64 + 8n). */
static int64_t mac_of(const uint8_t key[16], uint32_t data_id, uint64_t session, uint64_t freshness,
                      const uint8_t* frame, int n_values) {
  uint8_t in[20 + 64 + 8 * MAX_VALUES];
  const int covered = 64 + 8 * n_values;
  put_le(in, data_id, 4);
  put_le(in + 4, session, 8);
  put_le(in + 12, freshness, 8);
  memcpy(in + 20, frame, (size_t)covered);
  uint8_t out[crypto_shorthash_siphash24_BYTES];
  crypto_shorthash_siphash24(out, in, (unsigned long long)(20 + covered), key);
  uint64_t tag = 0;
  for (int i = 7; i >= 0; --i) tag = (tag << 8) | out[i];
  return (int64_t)tag;
}

/* 32 hexadecimal digits, whitespace and # comments allowed, readable by its owner only (docs/transport.md). */
static int read_key(const char* path, uint8_t key[16]) {
  struct stat st;
  if (stat(path, &st) != 0) {
    fprintf(stderr, "interop_controller: key file %s: %s\n", path, strerror(errno));
    return 0;
  }
  if ((st.st_mode & 077) != 0) {
    fprintf(stderr, "interop_controller: key file %s must be readable by its owner only (chmod 600)\n", path);
    return 0;
  }
  FILE* f = fopen(path, "r");
  if (!f) return 0;
  int digits = 0, c, comment = 0;
  while ((c = fgetc(f)) != EOF) {
    if (comment) {
      if (c == '\n') comment = 0;
      continue;
    }
    if (c == '#') {
      comment = 1;
      continue;
    }
    if (isspace(c)) continue;
    if (!isxdigit(c) || digits == 32) {
      fclose(f);
      fprintf(stderr, "interop_controller: key file %s: not 32 hexadecimal digits\n", path);
      return 0;
    }
    const int nibble = isdigit(c) ? c - '0' : tolower(c) - 'a' + 10;
    if (digits % 2 == 0) key[digits / 2] = (uint8_t)(nibble << 4);
    else key[digits / 2] |= (uint8_t)nibble;
    ++digits;
  }
  fclose(f);
  if (digits != 32) {
    fprintf(stderr, "interop_controller: key file %s: %d hexadecimal digits, 32 needed\n", path, digits);
    return 0;
  }
  return 1;
}

/* ---------------------------------------------------------------------------------------------------------
 * The link. */

#define END_OF_RUN_SENSOR (1u << 31)
#define END_OF_RUN_ACK (1u << 11)
#define RESEND_GAP_NS 20000000LL
#define END_LINGER_NS 40000000LL

typedef struct {
  device_t dev;
  lcm_t* lcm;
  char actuator_channel[128];
  uint64_t scene_hash;
  uint32_t own_id;
  int keyed;
  uint8_t key[16];
  int64_t tick_ns;
  monorail_law_t monorail;
  ship_law_t ship;
  /* link state */
  int bound;
  int64_t session, plant;
  uint64_t rx_freshness; /* latest accepted freshness of the plant */
  uint64_t tx_freshness; /* ours, 1, 2, 3, ... */
  uint32_t sequence;     /* ours, 0, 1, 2, ... per new frame */
  int64_t answered;      /* tick of our latest answer, -1 before the first */
  frame_t last;          /* our latest answer (header and commands) */
  int64_t last_send_ns;
  int ended;
  int64_t ended_at_ns;
  int64_t last_rx_ns;
  long lose_every; /* testing: every this many new answers one is lost on the way (0: none) */
  /* counters */
  long lost, foreign, other_scene, bad_mac, stale, answers, resends, end_acks;
} link_t;

static int64_t now_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (int64_t)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

/* Publish `last` with the next freshness and, keyed, its MAC. `lose`: the frame is counted as sent but never
 * reaches the bus (--lose-every: the plant's resend rule and ours are then exercised). */
static void publish_frame(link_t* L, int lose) {
  uint8_t buf[256];
  L->last.freshness = (int64_t)++L->tx_freshness;
  L->last.mac = 0;
  int len = encode_actuator(L->dev, &L->last, buf, sizeof buf);
  if (len != 88 + 8 * COMMAND_VALUES) {
    fprintf(stderr, "interop_controller: encoding failed (%d)\n", len);
    exit(3);
  }
  if (L->keyed) {
    L->last.mac = mac_of(L->key, DATA_ID_ACTUATOR, (uint64_t)L->session, L->tx_freshness, buf, COMMAND_VALUES);
    len = encode_actuator(L->dev, &L->last, buf, sizeof buf);
  }
  if (!lose && lcm_publish(L->lcm, L->actuator_channel, buf, (unsigned)len) != 0) {
    fprintf(stderr, "interop_controller: publish failed\n");
    exit(3);
  }
  L->last_send_ns = now_ns();
}

static void publish_last(link_t* L) { publish_frame(L, 0); }

static void on_sensor(const lcm_recv_buf_t* rbuf, const char* channel, void* user) {
  (void)channel;
  link_t* L = (link_t*)user;
  frame_t f;
  if (!decode_sensor(L->dev, rbuf->data, (int)rbuf->data_size, &f)) return; /* not the device's frame */
  if (f.session == 0) return;                                               /* a recording */
  if (!L->bound) {
    if (f.tick != 0) return; /* a plant already running belongs to someone else */
  } else if (f.session != L->session || f.sender != L->plant) {
    ++L->foreign;
    return;
  }
  if ((uint64_t)f.scene != L->scene_hash) {
    ++L->other_scene;
    if (L->other_scene == 1) {
      fprintf(stderr, "interop_controller: refusing frames of scene %016llx (ours %016llx)\n",
              (unsigned long long)f.scene, (unsigned long long)L->scene_hash);
    }
    return;
  }
  if (L->keyed) {
    const uint64_t fr = (uint64_t)f.freshness;
    const int64_t tag =
        mac_of(L->key, DATA_ID_SENSOR, (uint64_t)f.session, fr, (const uint8_t*)rbuf->data, SENSOR_VALUES);
    if (tag != f.mac || fr <= L->rx_freshness || fr - L->rx_freshness > 1024) {
      ++L->bad_mac;
      return;
    }
    L->rx_freshness = fr;
  }
  if (!L->bound) {
    L->bound = 1;
    L->session = f.session;
    L->plant = f.sender;
    L->last.scene = (int64_t)L->scene_hash; /* the envelope of every frame we send from now on */
    L->last.sender = (int64_t)L->own_id;
    L->last.session = L->session;
  }
  L->last_rx_ns = now_ns();

  if (L->ended) { /* copies of the end-of-run frame within the linger: answer them again */
    if (((uint32_t)f.status & END_OF_RUN_SENSOR) && f.tick == L->last.tick) {
      publish_last(L);
      ++L->end_acks;
    }
    return;
  }
  if (f.tick == L->answered) { /* the plant did not get our answer: the same content, the next freshness */
    if (now_ns() - L->last_send_ns >= RESEND_GAP_NS) {
      publish_last(L);
      ++L->resends;
    }
    return;
  }
  if (f.tick != L->answered + 1) {
    ++L->stale;
    return;
  }
  if ((uint32_t)f.status & END_OF_RUN_SENSOR) {
    /* Not stepped on: tick N, status bit 11, the safe commands; sensor_tick as before, the next sequence. */
    L->last.tick = f.tick;
    L->last.time_ns = f.tick * L->tick_ns;
    L->last.sequence = (int32_t)L->sequence++;
    L->last.status = (int32_t)END_OF_RUN_ACK;
    L->last.v[0] = 0.0; /* torque: safe 0 */
    L->last.v[1] = 1.0; /* precession_brake: safe 1 */
    L->last.sim_time_us = f.tick * L->tick_ns / 1000;
    publish_last(L);
    ++L->end_acks;
    L->answered = f.tick;
    L->ended = 1;
    L->ended_at_ns = now_ns();
    return;
  }
  double cmd[COMMAND_VALUES];
  uint32_t status = L->dev == DEV_MONORAIL ? monorail_step(&L->monorail, f.v, cmd) : ship_step(&L->ship, f.v, cmd);
  if (!isfinite(cmd[0]) || !isfinite(cmd[1])) {
    cmd[0] = 0.0;
    cmd[1] = 1.0;
    status |= BIT_NON_FINITE_COMMAND;
  }
  L->last.tick = f.tick;
  L->last.time_ns = f.tick * L->tick_ns;
  L->last.third = f.tick;
  L->last.sequence = (int32_t)L->sequence++;
  L->last.status = (int32_t)status;
  L->last.v[0] = cmd[0];
  L->last.v[1] = cmd[1];
  L->last.sim_time_us = f.tick * L->tick_ns / 1000;
  ++L->answers;
  const int lose = L->lose_every > 0 && L->answers % L->lose_every == 0;
  publish_frame(L, lose);
  L->lost += lose;
  L->answered = f.tick;
}

static int configure(link_t* L, const scene_t* sc) {
  const char* device = scene_text(sc, "scene", "device");
  if (!device) {
    fprintf(stderr, "interop_controller: [scene] device missing\n");
    return 0;
  }
  const double tick_us = scene_number(sc, "loop", "tick_us", 1000.0);
  L->tick_ns = (int64_t)llround(tick_us * 1000.0);
  const double degree = 3.141592653589793 / 180.0;
  if (strcmp(device, "monorail") == 0) {
    L->dev = DEV_MONORAIL;
    L->monorail.k = scene_number(sc, "controller", "k", NAN);
    L->monorail.d = scene_number(sc, "controller", "d", NAN);
    L->monorail.limit = scene_number(sc, "controller", "torque_limit_Nm", 2000.0);
    return isfinite(L->monorail.k) && isfinite(L->monorail.d);
  }
  if (strcmp(device, "ship_roll_damper") == 0) {
    L->dev = DEV_SHIP;
    ship_law_t* p = &L->ship;
    const char* law = scene_text(sc, "controller", "law");
    p->active = law == NULL || strcmp(law, "active") == 0;
    const double units = scene_number(sc, "gyro", "units", 1.0);
    p->B = units * scene_number(sc, "gyro", "B", NAN);
    p->H = units * scene_number(sc, "gyro", "H", NAN);
    p->limit = scene_number(sc, "controller", "torque_limit_Nm", 2e5);
    p->d2 = scene_number(sc, "controller", "brake_d2", 45300.0);
    p->k_r = scene_number(sc, "controller", "roll_rate_gain", p->H);
    p->d_c = scene_number(sc, "controller", "precession_damping", 83600.0);
    p->k_c = scene_number(sc, "controller", "centring_stiffness", 0.0);
    p->beta_soft = degree * scene_number(sc, "controller", "soft_limit_deg", 60.0);
    p->w = degree * 10.0;
    p->k_s = scene_number(sc, "controller", "soft_stiffness", 5e5);
    p->a_b = scene_number(sc, "controller", "brake_deceleration", 2.0);
    p->delta_min = 1e-3;
    p->braking_direction = 0;
    return isfinite(p->B) && isfinite(p->H);
  }
  fprintf(stderr, "interop_controller: device %s is not one this controller knows\n", device);
  return 0;
}

int main(int argc, char** argv) {
  const char* scene_path = NULL;
  const char* key_path = NULL;
  const char* url = "udpm://239.255.76.67:7667?ttl=0";
  const char* suffix = "";
  long long id = -1;
  long timeout_ms = 1000, start_timeout_ms = 10000, lose_every = 0;
  for (int i = 1; i < argc; ++i) {
    const char* a = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : NULL;
    if (strcmp(a, "--key-file") == 0 && v) key_path = argv[++i];
    else if (strcmp(a, "--lcm-url") == 0 && v) url = argv[++i];
    else if (strcmp(a, "--channel-suffix") == 0 && v) suffix = argv[++i];
    else if (strcmp(a, "--id") == 0 && v) id = strtoll(argv[++i], NULL, 0);
    else if (strcmp(a, "--timeout-ms") == 0 && v) timeout_ms = strtol(argv[++i], NULL, 10);
    else if (strcmp(a, "--start-timeout-ms") == 0 && v) start_timeout_ms = strtol(argv[++i], NULL, 10);
    else if (strcmp(a, "--lose-every") == 0 && v) lose_every = strtol(argv[++i], NULL, 10);
    else if (a[0] != '-' && !scene_path) scene_path = a;
    else {
      fprintf(stderr, "usage: interop_controller SCENE.toml [--key-file FILE] [--lcm-url URL] "
                      "[--channel-suffix S] [--id N] [--timeout-ms MS] [--start-timeout-ms MS] [--lose-every N]\n");
      return 2;
    }
  }
  if (!scene_path || sodium_init() < 0) return 2;
  static scene_t scene;
  static link_t L;
  if (!read_scene(scene_path, &scene) || !configure(&L, &scene)) return 2;
  L.scene_hash = scene.hash;
  if (key_path) {
    if (!read_key(key_path, L.key)) return 2;
    L.keyed = 1;
  }
  if (id >= 0) {
    L.own_id = (uint32_t)id;
  }
  while (L.own_id == 0) L.own_id = randombytes_random();
  L.answered = -1;
  L.lose_every = lose_every;
  L.lcm = lcm_create(url);
  if (!L.lcm) {
    fprintf(stderr, "interop_controller: cannot open LCM at %s\n", url);
    return 3;
  }
  char sensor_channel[128];
  snprintf(sensor_channel, sizeof sensor_channel, "GYROSTAB_SENSOR%s", suffix);
  snprintf(L.actuator_channel, sizeof L.actuator_channel, "GYROSTAB_ACTUATOR%s", suffix);
  lcm_subscribe(L.lcm, sensor_channel, on_sensor, &L);
  const int64_t start = now_ns();
  L.last_rx_ns = start;
  for (;;) {
    const int r = lcm_handle_timeout(L.lcm, 5);
    if (r < 0) {
      fprintf(stderr, "interop_controller: LCM receive failed\n");
      return 3;
    }
    const int64_t t = now_ns();
    if (L.ended && t - L.ended_at_ns >= END_LINGER_NS) break;
    const long limit = L.bound ? timeout_ms : start_timeout_ms;
    if (t - L.last_rx_ns > (int64_t)limit * 1000000LL) {
      if (L.bound) {
        fprintf(stderr, "interop_controller: plant lost after tick %lld (%ld ms without a frame)\n",
                (long long)L.answered, limit);
      } else {
        fprintf(stderr, "interop_controller: no plant of scene %016llx within %ld ms (%ld frames of other scenes "
                        "refused)\n", (unsigned long long)L.scene_hash, limit, L.other_scene);
      }
      return 6;
    }
  }
  printf("interop_controller: end of run at tick %lld acknowledged; %ld answers (%ld lost on purpose), %ld resends, "
         "%ld end-of-run acknowledgements; refused: %ld foreign, %ld other scene, %ld MAC or freshness, %ld out of order\n",
         (long long)L.last.tick, L.answers, L.lost, L.resends, L.end_acks, L.foreign, L.other_scene, L.bad_mac, L.stale);
  lcm_destroy(L.lcm);
  return 0;
}
