// An independent reader of gyrostab's MCAP files: Foxglove's @mcap/core (npm), run with Debian's node. Reads the
// file twice — through its summary and indexes (McapIndexedReader, every chunk's and the summary's CRC checked)
// and record by record from the start (McapStreamReader, CRCs checked) — checks the data section's CRC with
// @foxglove/crc, then compares every message of /gyrostab/signals with signals.csv, value for value and bit for
// bit (JSON numbers and %.17g both read back to the same double), and /gyrostab/report with report.json.
//   node mcap_readback.cjs FILE.mcap signals.csv report.json
// Exit 0 and one summary line when everything matches; 1 with the first difference otherwise.
"use strict";
const fs = require("fs");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { crc32 } = require("@foxglove/crc");

function fail(msg) {
  console.error("mcap_readback: " + msg);
  process.exit(1);
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

async function main() {
  const [file, csvPath, reportPath] = process.argv.slice(2);
  if (!reportPath) fail("usage: node mcap_readback.cjs FILE.mcap signals.csv report.json");
  const bytes = new Uint8Array(fs.readFileSync(file));
  const csv = csvTable(fs.readFileSync(csvPath, "utf8"));
  const report = JSON.parse(fs.readFileSync(reportPath, "utf8"));
  const tickNs = BigInt(report.scene.tick_ns);
  const decoder = new TextDecoder();

  // 1. Indexed: footer, summary (its CRC), chunk indexes, then every message through the indexes.
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
  };
  const reader = await McapIndexedReader.Initialize({ readable });
  const topics = new Map([...reader.channelsById.values()].map((c) => [c.id, c]));
  const signals = [...topics.values()].find((c) => c.topic === "/gyrostab/signals");
  const reportChannel = [...topics.values()].find((c) => c.topic === "/gyrostab/report");
  if (!signals || !reportChannel) fail("channels /gyrostab/signals and /gyrostab/report expected");
  for (const c of [signals, reportChannel]) {
    const schema = reader.schemasById.get(c.schemaId);
    if (!schema || schema.encoding !== "jsonschema" || c.messageEncoding !== "json") {
      fail(`${c.topic}: expected a jsonschema schema and json messages`);
    }
  }
  const sigSchema = JSON.parse(decoder.decode(reader.schemasById.get(signals.schemaId).data));
  for (const name of csv.columns) {
    if (!sigSchema.properties || !sigSchema.properties[name]) fail(`schema has no property ${name}`);
  }
  if (reader.chunkIndexes.length === 0) fail("no chunk index");
  const stats = reader.statistics;
  if (!stats) fail("no statistics record");

  let row = 0, reportSeen = 0, total = 0;
  for await (const m of reader.readMessages({ validateCrcs: true })) {
    total++;
    const value = JSON.parse(decoder.decode(m.data));
    if (m.channelId === signals.id) {
      if (row >= csv.rows.length) fail(`more signal messages than CSV rows (${csv.rows.length})`);
      const expected = csv.rows[row];
      csv.columns.forEach((name, j) => {
        if (!same(expected[j], value[name])) {
          fail(`row ${row} ${name}: csv ${expected[j]} vs mcap ${value[name]}`);
        }
      });
      if (m.logTime !== BigInt(value.tick) * tickNs || m.publishTime !== m.logTime) {
        fail(`row ${row}: log time ${m.logTime} is not tick ${value.tick} x ${tickNs} ns`);
      }
      if (Math.abs(Number(m.logTime) * 1e-9 - value.t_s) > 1e-9 * Math.max(1, value.t_s)) {
        fail(`row ${row}: log time ${m.logTime} ns vs t_s ${value.t_s}`);
      }
      if (m.sequence !== row) fail(`row ${row}: sequence ${m.sequence}`);
      row++;
    } else if (m.channelId === reportChannel.id) {
      reportSeen++;
      const d = deepEqual(value, report, "report");
      if (d) fail("report message differs from report.json: " + d);
    } else {
      fail(`message on unexpected channel ${m.channelId}`);
    }
  }
  if (row !== csv.rows.length) fail(`${row} signal messages for ${csv.rows.length} CSV rows`);
  if (reportSeen !== 1) fail(`${reportSeen} report messages`);
  if (stats.messageCount !== BigInt(total)) fail(`statistics count ${stats.messageCount} vs ${total} read`);
  if (stats.channelMessageCounts.get(signals.id) !== BigInt(row)) fail("statistics: signal count differs");

  // 2. Streamed, record by record, chunk CRCs checked; and the data section's CRC, computed here.
  const stream = new McapStreamReader({ validateCrcs: true });
  stream.append(bytes);
  let streamed = 0, offset = 0, dataEnd = null, footer = null, dataEndAt = -1;
  for (let rec; (rec = stream.nextRecord()); ) {
    if (rec.type === "Message") streamed++;
    if (rec.type === "DataEnd") dataEnd = rec;
    if (rec.type === "Footer") footer = rec;
  }
  if (!stream.done()) fail("the stream reader did not reach the end");
  if (streamed !== total) fail(`stream reader read ${streamed} messages, indexed ${total}`);
  if (!dataEnd || !footer) fail("no data-end or footer record");
  dataEndAt = Number(footer.summaryStart) - (1 + 8 + 4);
  offset = dataEndAt;
  if (bytes[offset] !== 0x0f) fail("the data-end record is not just before the summary");
  const crc = crc32(bytes.subarray(0, dataEndAt));
  if (dataEnd.dataSectionCrc !== crc) fail(`data section CRC ${dataEnd.dataSectionCrc} vs ${crc} computed`);

  console.log(`mcap_readback: ${file}: ${total} messages (${row} rows x ${csv.columns.length} signals + report), ` +
              `${reader.chunkIndexes.length} chunks, ${bytes.length} bytes; every value equals signals.csv`);
}

main().catch((e) => fail(e && e.stack ? e.stack : String(e)));
