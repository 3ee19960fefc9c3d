#include "tools/log/mcap_writer.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>

namespace gyrostab::mcap {

namespace {

constexpr char kMagic[] = {'\x89', 'M', 'C', 'A', 'P', '0', '\r', '\n'};

enum Op : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

constexpr std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[n] = c;
  }
  return t;
}
constexpr std::array<std::uint32_t, 256> kCrcTable = make_crc_table();

// Little-endian appends: the specification's primitive types.
void u8(std::string& b, std::uint8_t v) { b.push_back(static_cast<char>(v)); }
void u16(std::string& b, std::uint16_t v) {
  for (int i = 0; i < 2; ++i) b.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}
void u32(std::string& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}
void u64(std::string& b, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) b.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}
// String and Bytes with a uint32 length.
void str(std::string& b, std::string_view s) {
  u32(b, static_cast<std::uint32_t>(s.size()));
  b.append(s);
}
// <opcode><uint64 length><body>
void record(std::string& out, std::uint8_t op, std::string_view body) {
  u8(out, op);
  u64(out, body.size());
  out.append(body);
}

}  // namespace

std::uint32_t crc32(std::uint32_t crc, const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::uint32_t c = crc ^ 0xFFFFFFFFu;
  for (std::size_t i = 0; i < size; ++i) c = kCrcTable[(c ^ p[i]) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

Writer::~Writer() { abandon(); }

void Writer::abandon() {
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
  ok_ = false;
}

bool Writer::open(const std::string& path, const WriterOptions& options, std::string& error) {
  abandon();
  options_ = options;
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) {
    error = "cannot create " + path + ": " + std::strerror(errno);
    return false;
  }
  ok_ = true;
  offset_ = 0;
  data_crc_ = 0;
  emit(std::string_view(kMagic, sizeof kMagic));
  std::string body, rec;
  str(body, options_.profile);
  str(body, options_.library);
  record(rec, kHeader, body);
  emit(rec);
  return ok_;
}

void Writer::emit(std::string_view bytes) {
  if (!ok_) return;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) ok_ = false;
  data_crc_ = crc32(data_crc_, bytes.data(), bytes.size());
  offset_ += bytes.size();
}

std::string Writer::schema_record(const Schema& s) {
  std::string body, rec;
  u16(body, s.id);
  str(body, s.name);
  str(body, s.encoding);
  str(body, s.data);
  record(rec, kSchema, body);
  return rec;
}

std::string Writer::channel_record(const Channel& c) {
  std::string body, rec, map;
  u16(body, c.id);
  u16(body, c.schema_id);
  str(body, c.topic);
  str(body, c.encoding);
  for (const auto& [k, v] : c.metadata) {
    str(map, k);
    str(map, v);
  }
  str(body, map);  // Map<string, string>: uint32 byte length, then the pairs
  record(rec, kChannel, body);
  return rec;
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding, std::string_view data) {
  const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);  // 0 means "no schema"
  schemas_.push_back({id, name, encoding, std::string(data)});
  return id;
}

std::uint16_t Writer::add_channel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                                  const std::map<std::string, std::string>& metadata) {
  const auto id = static_cast<std::uint16_t>(channels_.size());
  Channel c{id, schema_id, topic, message_encoding, metadata};
  channels_.push_back(std::move(c));
  return id;
}

bool Writer::write(std::uint16_t channel_id, std::uint64_t log_time, std::uint64_t publish_time, std::string_view data) {
  if (!ok_ || channel_id >= channels_.size()) return false;
  Channel& c = channels_[channel_id];
  // A chunk is readable alone: the schema and channel records of its messages come first inside it.
  if (!c.in_chunk) {
    if (c.schema_id != 0) chunk_ += schema_record(schemas_[c.schema_id - 1]);
    chunk_ += channel_record(c);
    c.in_chunk = true;
  }
  const std::uint64_t at = chunk_.size();
  u8(chunk_, kMessage);
  u64(chunk_, 2 + 4 + 8 + 8 + data.size());
  u16(chunk_, channel_id);
  u32(chunk_, static_cast<std::uint32_t>(c.count));
  u64(chunk_, log_time);
  u64(chunk_, publish_time);
  chunk_.append(data);
  ++c.count;
  chunk_index_[channel_id].emplace_back(log_time, at);
  if (!chunk_has_messages_ || log_time < chunk_start_) chunk_start_ = log_time;
  if (!chunk_has_messages_ || log_time > chunk_end_) chunk_end_ = log_time;
  if (message_count_ == 0 || log_time < start_time_) start_time_ = log_time;
  if (message_count_ == 0 || log_time > end_time_) end_time_ = log_time;
  chunk_has_messages_ = true;
  ++message_count_;
  if (chunk_.size() >= options_.chunk_size) return flush_chunk();
  return ok_;
}

bool Writer::flush_chunk() {
  if (chunk_.empty()) return ok_;
  ChunkIndex ix{};
  ix.start_time = chunk_start_;
  ix.end_time = chunk_end_;
  ix.offset = offset_;
  ix.size = chunk_.size();
  std::string body, rec;
  u64(body, chunk_start_);
  u64(body, chunk_end_);
  u64(body, chunk_.size());  // uncompressed size
  u32(body, crc32(0, chunk_.data(), chunk_.size()));
  str(body, "");  // no compression
  u64(body, chunk_.size());
  body += chunk_;
  record(rec, kChunk, body);
  emit(rec);
  ix.length = rec.size();
  const std::uint64_t index_start = offset_;
  for (const auto& [channel, entries] : chunk_index_) {
    std::string ib, ir;
    u16(ib, channel);
    u32(ib, static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [t, at] : entries) {
      u64(ib, t);
      u64(ib, at);
    }
    ix.index_offsets.emplace_back(channel, offset_);
    record(ir, kMessageIndex, ib);
    emit(ir);
  }
  ix.index_length = offset_ - index_start;
  chunk_indexes_.push_back(std::move(ix));
  chunk_.clear();
  chunk_index_.clear();
  chunk_has_messages_ = false;
  for (Channel& c : channels_) c.in_chunk = false;
  return ok_;
}

bool Writer::close(std::string& error) {
  if (file_ == nullptr) {
    error = "the MCAP file is not open";
    return false;
  }
  flush_chunk();
  std::string rec, body;
  u32(body, data_crc_);  // everything from the leading magic to here
  record(rec, kDataEnd, body);
  emit(rec);

  // The summary, in groups of one record kind each; its CRC runs from here through the footer's offsets.
  const std::uint64_t summary_start = offset_;
  data_crc_ = 0;
  std::vector<std::pair<std::uint8_t, std::pair<std::uint64_t, std::uint64_t>>> groups;
  auto group = [&](std::uint8_t op, const std::string& records) {
    if (records.empty()) return;
    groups.push_back({op, {offset_, records.size()}});
    emit(records);
  };
  std::string s;
  for (const Schema& sc : schemas_) s += schema_record(sc);
  group(kSchema, s);
  s.clear();
  for (const Channel& c : channels_) s += channel_record(c);
  group(kChannel, s);
  s.clear();
  {
    std::string st, counts;
    u64(st, message_count_);
    u16(st, static_cast<std::uint16_t>(schemas_.size()));
    u32(st, static_cast<std::uint32_t>(channels_.size()));
    u32(st, 0);  // attachments
    u32(st, 0);  // metadata
    u32(st, static_cast<std::uint32_t>(chunk_indexes_.size()));
    u64(st, start_time_);
    u64(st, end_time_);
    for (const Channel& c : channels_) {
      u16(counts, c.id);
      u64(counts, c.count);
    }
    str(st, counts);
    record(s, kStatistics, st);
  }
  group(kStatistics, s);
  s.clear();
  for (const ChunkIndex& ix : chunk_indexes_) {
    std::string b, offsets;
    u64(b, ix.start_time);
    u64(b, ix.end_time);
    u64(b, ix.offset);
    u64(b, ix.length);
    for (const auto& [channel, at] : ix.index_offsets) {
      u16(offsets, channel);
      u64(offsets, at);
    }
    str(b, offsets);
    u64(b, ix.index_length);
    str(b, "");
    u64(b, ix.size);  // compressed size = uncompressed size
    u64(b, ix.size);
    record(s, kChunkIndex, b);
  }
  group(kChunkIndex, s);

  const std::uint64_t summary_offset_start = offset_;
  for (const auto& [op, span] : groups) {
    std::string b, r;
    u8(b, op);
    u64(b, span.first);
    u64(b, span.second);
    record(r, kSummaryOffset, b);
    emit(r);
  }
  std::string footer;
  u8(footer, kFooter);
  u64(footer, 8 + 8 + 4);
  u64(footer, summary_start);
  u64(footer, summary_offset_start);
  emit(footer);
  std::string tail;
  u32(tail, data_crc_);
  tail.append(kMagic, sizeof kMagic);
  emit(tail);

  const bool wrote = ok_;
  const bool flushed = std::fflush(file_) == 0 && std::ferror(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  ok_ = false;
  if (!wrote || !flushed || !closed) {
    error = "error writing the MCAP file";
    return false;
  }
  return true;
}

}  // namespace gyrostab::mcap
