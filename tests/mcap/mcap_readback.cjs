// An independent reader of gyrostab's MCAP files: Foxglove's @mcap/core (npm), run with Debian's node. Reads the
// file twice — through its summary and indexes (McapIndexedReader, every chunk's and the summary's CRC checked)
// and record by record from the start (McapStreamReader, CRCs checked) — checks the data section's CRC with
// @foxglove/crc, then compares the messages with what the run wrote:
//   node mcap_readback.cjs FILE.mcap [--csv signals.csv --report report.json] [--frames-every N]
//                                    [--bus-log LOG] [--export SCENE_FILE [--incomplete]]
//   --csv/--report  every message of /gyrostab/signals against signals.csv, value for value and bit for bit (JSON
//                   numbers and %.17g both read back to the same double), /gyrostab/report against report.json;
//   --frames-every  /gyrostab/sensor and /gyrostab/actuator hold the frames of every N-th tick: their ticks, log
//                   times, sequence numbers and fields (each schema property a number, integer or array, with
//                   a description), and as many messages as the run had such ticks (0: no frame channels);
//   --bus-log       every frame message against the bus log's frame of the same tick, decoded here from LCM's
//                   event-log format and the frames' big-endian wire layout (not by gyrostab's reader): header
//                   and every signal, bit for bit;
//   --export        a `gyrostab export` file: /gyrostab/scene carries SCENE_FILE's text byte for byte,
//                   /gyrostab/log says the log was complete (or, with --incomplete, that it was not, with the
//                   reader's problem), and the frames cover every whole tick of the log.
//   --prefix        the file exports part of the bus log's ticks (a cut or damaged candump log of the same run):
//                   each frame is checked against the bus log, their number against the file's own ticks_read.
// Exit 0 and one summary line when everything matches; 1 with the first difference otherwise.
"use strict";
const fs = require("fs");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { crc32 } = require("@foxglove/crc");

function fail(msg) {
  console.error("mcap_readback: " + msg);
  process.exit(1);
}

function args(argv) {
  const a = { file: argv[0], framesEvery: null };
  for (let i = 1; i < argv.length; i++) {
    const k = argv[i];
    if (k === "--csv") a.csv = argv[++i];
    else if (k === "--report") a.report = argv[++i];
    else if (k === "--frames-every") a.framesEvery = Number(argv[++i]);
    else if (k === "--bus-log") a.busLog = argv[++i];
    else if (k === "--export") a.exportScene = argv[++i];
    else if (k === "--incomplete") a.incomplete = true;
    else if (k === "--prefix") a.prefix = true;
    else fail("unknown argument " + k);
  }
  if (!a.file) fail("usage: node mcap_readback.cjs FILE.mcap [--csv CSV --report JSON] [--frames-every N] [--bus-log LOG] [--export SCENE]");
  return a;
}

function csvTable(text) {
  const lines = text.split("\n").filter((l) => l.length > 0);
  const columns = lines[0].split(",");
  const rows = lines.slice(1).map((l) => l.split(",").map((v) => Number(v)));
  return { columns, rows };
}

function same(a, b) {
  // JSON has no NaN or infinity: the writer puts null where the CSV has nan/inf.
  if (b === null) return !Number.isFinite(a);
  return Object.is(a, b);
}

function deepEqual(a, b, path) {
  if (typeof a !== typeof b) return `${path}: ${typeof a} vs ${typeof b}`;
  if (a === null || b === null) return a === b ? "" : `${path}: ${a} vs ${b}`;
  if (Array.isArray(a)) {
    if (!Array.isArray(b) || a.length !== b.length) return `${path}: arrays differ in length`;
    for (let i = 0; i < a.length; i++) {
      const d = deepEqual(a[i], b[i], `${path}[${i}]`);
      if (d) return d;
    }
    return "";
  }
  if (typeof a === "object") {
    const ka = Object.keys(a).sort(), kb = Object.keys(b).sort();
    if (ka.join(",") !== kb.join(",")) return `${path}: keys ${ka} vs ${kb}`;
    for (const k of ka) {
      const d = deepEqual(a[k], b[k], `${path}.${k}`);
      if (d) return d;
    }
    return "";
  }
  return Object.is(a, b) ? "" : `${path}: ${a} vs ${b}`;
}

// LCM's event log (lcm/eventlog.c): per event the sync word 0xEDA1DA01, event number, timestamp (int64),
// channel length, data length (int32), channel, data; big-endian. A cut event ends the reading.
function readBusLog(path) {
  const b = fs.readFileSync(path);
  const frames = { sensor: new Map(), actuator: new Map() };
  let at = 0, pairs = 0, pendingSensor = null;
  while (at + 28 <= b.length) {
    if (b.readUInt32BE(at) !== 0xeda1da01) break;
    const chLen = b.readInt32BE(at + 20), dataLen = b.readInt32BE(at + 24);
    if (at + 28 + chLen + dataLen > b.length) break;
    const channel = b.toString("latin1", at + 28, at + 28 + chLen);
    const data = b.subarray(at + 28 + chLen, at + 28 + chLen + dataLen);
    at += 28 + chLen + dataLen;
    const sensor = channel.startsWith("GYROSTAB_SENSOR"), actuator = channel.startsWith("GYROSTAB_ACTUATOR");
    if (!sensor && !actuator) continue;
    // fingerprint, tick, time_ns, sample_time_ns | sensor_tick (int64), sequence, status (int32), the doubles,
    // sim_time_us, the scene hash and the envelope (6 x int64: docs/protocol.md).
    const n = (data.length - 8 - 32 - 48) / 8;
    const f = {
      tick: Number(data.readBigInt64BE(8)),
      time_ns: Number(data.readBigInt64BE(16)),
      third: Number(data.readBigInt64BE(24)),
      sequence: data.readUInt32BE(32),
      status: data.readUInt32BE(36),
      values: Array.from({ length: n }, (_, i) => data.readDoubleBE(40 + 8 * i)),
    };
    if (sensor) pendingSensor = f;
    else if (pendingSensor && pendingSensor.tick === f.tick) {
      frames.sensor.set(f.tick, pendingSensor);
      frames.actuator.set(f.tick, f);
      pendingSensor = null;
      pairs++;
    }
  }
  return { frames, ticks: pairs };
}

// A frame message's fields in schema order, arrays flattened: [{name, value}] after "tick".
function flatten(schema, value) {
  const out = [];
  for (const [name, p] of Object.entries(schema.properties)) {
    if (name === "tick") continue;
    if (p.type === "array") value[name].forEach((v, i) => out.push({ name: `${name}[${i}]`, value: v, p }));
    else out.push({ name, value: value[name], p });
  }
  return out;
}

async function main() {
  const a = args(process.argv.slice(2));
  const bytes = new Uint8Array(fs.readFileSync(a.file));
  const csv = a.csv ? csvTable(fs.readFileSync(a.csv, "utf8")) : null;
  const report = a.report ? JSON.parse(fs.readFileSync(a.report, "utf8")) : null;
  const bus = a.busLog ? readBusLog(a.busLog) : null;
  const decoder = new TextDecoder();

  // 1. Indexed: footer, summary (its CRC), chunk indexes, then every message through the indexes.
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
  };
  const reader = await McapIndexedReader.Initialize({ readable });
  const byTopic = new Map([...reader.channelsById.values()].map((c) => [c.topic, c]));
  const expectTopics = a.exportScene
    ? ["/gyrostab/scene", "/gyrostab/sensor", "/gyrostab/actuator", "/gyrostab/log"]
    : ["/gyrostab/signals", "/gyrostab/report"].concat(a.framesEvery ? ["/gyrostab/sensor", "/gyrostab/actuator"] : []);
  for (const t of expectTopics) if (!byTopic.has(t)) fail(`channel ${t} expected`);
  if (byTopic.size !== expectTopics.length) fail(`channels ${[...byTopic.keys()]}, expected ${expectTopics}`);
  const schemaOf = (c) => {
    const s = reader.schemasById.get(c.schemaId);
    if (!s || s.encoding !== "jsonschema" || c.messageEncoding !== "json") fail(`${c.topic}: expected a jsonschema schema and json messages`);
    return JSON.parse(decoder.decode(s.data));
  };
  const schemas = new Map([...byTopic.values()].map((c) => [c.id, schemaOf(c)]));
  const signals = byTopic.get("/gyrostab/signals");
  if (signals && csv) {
    const sigSchema = schemas.get(signals.id);
    for (const name of csv.columns) if (!sigSchema.properties || !sigSchema.properties[name]) fail(`schema has no property ${name}`);
  }
  const frameTopics = new Map();  // channel id -> {kind, schema, count, lastTick}
  for (const kind of ["sensor", "actuator"]) {
    const c = byTopic.get(`/gyrostab/${kind}`);
    if (!c) continue;
    const schema = schemas.get(c.id);
    for (const [name, p] of Object.entries(schema.properties)) {
      const t = p.type === "array" ? p.items.type : p.type;
      const ok = name === "tick" ? t === "integer" : (t === "integer" || JSON.stringify(t) === '["number","null"]');
      if (!ok) fail(`${c.topic}.${name}: type ${JSON.stringify(t)}`);
      if (name !== "tick" && !(p.description && p.description.includes("["))) fail(`${c.topic}.${name}: no description with a unit`);
    }
    frameTopics.set(c.id, { kind, schema, count: 0, lastTick: -1 });
  }
  if (reader.chunkIndexes.length === 0) fail("no chunk index");
  const stats = reader.statistics;
  if (!stats) fail("no statistics record");
  const tickNs = BigInt(report ? report.scene.tick_ns : 0);

  let row = 0, reportSeen = 0, total = 0, sceneMsg = null, logMsg = null, frameValues = 0;
  for await (const m of reader.readMessages({ validateCrcs: true })) {
    total++;
    const value = JSON.parse(decoder.decode(m.data));
    const c = reader.channelsById.get(m.channelId);
    if (signals && m.channelId === signals.id) {
      if (!csv) continue;
      if (row >= csv.rows.length) fail(`more signal messages than CSV rows (${csv.rows.length})`);
      const expected = csv.rows[row];
      csv.columns.forEach((name, j) => {
        if (!same(expected[j], value[name])) fail(`row ${row} ${name}: csv ${expected[j]} vs mcap ${value[name]}`);
      });
      if (m.logTime !== BigInt(value.tick) * tickNs || m.publishTime !== m.logTime) {
        fail(`row ${row}: log time ${m.logTime} is not tick ${value.tick} x ${tickNs} ns`);
      }
      if (Math.abs(Number(m.logTime) * 1e-9 - value.t_s) > 1e-9 * Math.max(1, value.t_s)) {
        fail(`row ${row}: log time ${m.logTime} ns vs t_s ${value.t_s}`);
      }
      if (m.sequence !== row) fail(`row ${row}: sequence ${m.sequence}`);
      row++;
    } else if (c.topic === "/gyrostab/report") {
      reportSeen++;
      if (report) {
        const d = deepEqual(value, report, "report");
        if (d) fail("report message differs from report.json: " + d);
      }
    } else if (frameTopics.has(m.channelId)) {
      const ft = frameTopics.get(m.channelId);
      if (value.tick <= ft.lastTick) fail(`${c.topic}: tick ${value.tick} after ${ft.lastTick}`);
      if (a.framesEvery && value.tick % a.framesEvery !== 0) fail(`${c.topic}: tick ${value.tick} is not a multiple of ${a.framesEvery}`);
      if (m.sequence !== ft.count) fail(`${c.topic}: sequence ${m.sequence} for message ${ft.count}`);
      if (tickNs > 0n && m.logTime !== BigInt(value.tick) * tickNs) fail(`${c.topic}: log time ${m.logTime} for tick ${value.tick}`);
      if (value.time_ns !== Number(m.logTime)) fail(`${c.topic}: time_ns ${value.time_ns} vs log time ${m.logTime}`);
      ft.lastTick = value.tick;
      ft.count++;
      if (bus) {
        const f = bus.frames[ft.kind].get(value.tick);
        if (!f) fail(`${c.topic}: tick ${value.tick} is not in the bus log`);
        const third = ft.kind === "sensor" ? "sample_time_ns" : "sensor_tick";
        const header = { time_ns: f.time_ns, [third]: f.third, sequence: f.sequence, status: f.status };
        const fields = flatten(ft.schema, value);
        fields.forEach((x, i) => {
          const want = i < 4 ? header[x.name] : f.values[i - 4];
          if (want === undefined) fail(`${c.topic} tick ${value.tick}: field ${x.name} has no counterpart in the log's frame`);
          if (!same(want, x.value)) fail(`${c.topic} tick ${value.tick} ${x.name}: bus log ${want} vs mcap ${x.value}`);
        });
        if (fields.length - 4 !== f.values.length) fail(`${c.topic}: ${fields.length - 4} signals vs ${f.values.length} in the log's frame`);
        frameValues += fields.length;
      }
    } else if (c.topic === "/gyrostab/scene") {
      sceneMsg = value;
    } else if (c.topic === "/gyrostab/log") {
      logMsg = value;
    } else {
      fail(`message on unexpected channel ${c.topic}`);
    }
  }
  if (csv && row !== csv.rows.length) fail(`${row} signal messages for ${csv.rows.length} CSV rows`);
  if (!a.exportScene && reportSeen !== 1) fail(`${reportSeen} report messages`);
  if (stats.messageCount !== BigInt(total)) fail(`statistics count ${stats.messageCount} vs ${total} read`);
  if (signals && stats.channelMessageCounts.get(signals.id) !== BigInt(row)) fail("statistics: signal count differs");
  const counts = [...frameTopics.values()].map((f) => f.count);
  if (a.framesEvery && report) {
    const ticks = report.timing.ticks;
    const want = ticks > 0 ? Math.floor((ticks - 1) / a.framesEvery) + 1 : 0;
    for (const f of frameTopics.values()) if (f.count !== want) fail(`/gyrostab/${f.kind}: ${f.count} messages for ${want} ticks`);
  }
  if (bus && a.framesEvery && !a.prefix) {
    const want = Math.floor((bus.ticks - 1) / a.framesEvery) + 1;
    for (const f of frameTopics.values()) if (f.count !== want) fail(`/gyrostab/${f.kind}: ${f.count} messages, the bus log has ${want} such ticks`);
  }
  if (a.exportScene) {
    const text = fs.readFileSync(a.exportScene, "utf8");
    if (!sceneMsg || sceneMsg.toml !== text) fail("/gyrostab/scene does not carry the scene file's text");
    if (!logMsg) fail("no /gyrostab/log message");
    if (logMsg.complete !== !a.incomplete) fail(`/gyrostab/log complete ${logMsg.complete}`);
    if (a.incomplete && !(logMsg.problem && logMsg.problem_offset > 0)) fail("an incomplete log's message names no problem");
    if (a.prefix && a.framesEvery === 1) {
      for (const f of frameTopics.values()) if (f.count !== logMsg.ticks_read) fail(`/gyrostab/${f.kind}: ${f.count} messages, /gyrostab/log says ${logMsg.ticks_read} ticks`);
    }
    if (bus && !a.prefix && logMsg.ticks_read !== bus.ticks) fail(`/gyrostab/log ticks_read ${logMsg.ticks_read}, the log has ${bus.ticks} whole ticks`);
  }

  // 2. Streamed, record by record, chunk CRCs checked; and the data section's CRC, computed here.
  const stream = new McapStreamReader({ validateCrcs: true });
  stream.append(bytes);
  let streamed = 0, dataEnd = null, footer = null;
  for (let rec; (rec = stream.nextRecord()); ) {
    if (rec.type === "Message") streamed++;
    if (rec.type === "DataEnd") dataEnd = rec;
    if (rec.type === "Footer") footer = rec;
  }
  if (!stream.done()) fail("the stream reader did not reach the end");
  if (streamed !== total) fail(`stream reader read ${streamed} messages, indexed ${total}`);
  if (!dataEnd || !footer) fail("no data-end or footer record");
  const dataEndAt = Number(footer.summaryStart) - (1 + 8 + 4);
  if (bytes[dataEndAt] !== 0x0f) fail("the data-end record is not just before the summary");
  const crc = crc32(bytes.subarray(0, dataEndAt));
  if (dataEnd.dataSectionCrc !== crc) fail(`data section CRC ${dataEnd.dataSectionCrc} vs ${crc} computed`);

  const parts = [];
  if (csv) parts.push(`${row} rows x ${csv.columns.length} signals equal signals.csv`);
  if (counts.length) parts.push(`${counts.join(" + ")} frames`);
  if (bus) parts.push(`${frameValues} frame values equal the bus log's`);
  if (a.exportScene) parts.push(`scene and log messages (${logMsg.complete ? "complete" : "incomplete: " + logMsg.problem})`);
  console.log(`mcap_readback: ${a.file}: ${total} messages, ${reader.chunkIndexes.length} chunks, ${bytes.length} bytes; ` +
              parts.join("; "));
}

main().catch((e) => fail(e && e.stack ? e.stack : String(e)));
