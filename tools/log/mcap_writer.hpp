// An MCAP writer (the container Foxglove, Lichtblick and PlotJuggler open), written from the published format
// specification, version 0 (mcap.dev/spec): magic, header, schema and channel records, messages in chunks
// (uncompressed: every reader decodes them without a codec, and a run's rows are written once at its end, so the
// size is what the disk sees, not what a network carries), a message index per channel after each chunk, then
// the data-end record with the CRC-32 of everything before it, a summary section (schemas, channels,
// statistics, chunk indexes), summary offsets, the footer with the summary's CRC-32, and the magic again.
// Integers little-endian; times in nanoseconds (a run writes simulated time).
//
// Not for the loop thread: it allocates (the chunk buffer grows to its target size, the index per message).
// Docs: docs/mcap.md.
#pragma once

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gyrostab::mcap {

// CRC-32 (IEEE 802.3, reflected, as zlib's crc32) of `data` continued from `crc` (0 to start).
std::uint32_t crc32(std::uint32_t crc, const void* data, std::size_t size);

struct WriterOptions {
  std::string profile;                  // header profile: "" (none of the well-known ones applies)
  std::string library{"gyrostab"};      // header library
  std::size_t chunk_size{1u << 20};     // a chunk is closed once its records pass this many bytes
};

class Writer {
 public:
  Writer() = default;
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Creates `path` (truncating it) and writes the magic and the header; false with `error` set.
  bool open(const std::string& path, const WriterOptions& options, std::string& error);
  // A schema (e.g. encoding "jsonschema", data the JSON Schema text); its id (1, 2, ...).
  std::uint16_t add_schema(const std::string& name, const std::string& encoding, std::string_view data);
  // A channel on `topic` whose messages use `message_encoding` ("json") and schema `schema_id`; its id.
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});
  // One message; its sequence number is the channel's message count so far. false once a write failed.
  bool write(std::uint16_t channel_id, std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
             std::string_view data);
  // Closes the last chunk, writes the summary and the footer, closes the file; false with `error` set.
  bool close(std::string& error);
  // Drops the file's handle without completing it (the caller removes the file).
  void abandon();

  std::uint64_t bytes_written() const { return offset_; }

 private:
  struct Schema {
    std::uint16_t id;
    std::string name, encoding, data;
  };
  struct Channel {
    std::uint16_t id, schema_id;
    std::string topic, encoding;
    std::map<std::string, std::string> metadata;
    std::uint64_t count{0};
    bool in_chunk{false};  // written into the open chunk already
  };
  struct ChunkIndex {
    std::uint64_t start_time, end_time, offset, length;
    std::vector<std::pair<std::uint16_t, std::uint64_t>> index_offsets;
    std::uint64_t index_length, size;
  };

  void emit(std::string_view bytes);     // to the file, counting the offset and the data section's CRC
  bool flush_chunk();
  static std::string schema_record(const Schema& s);
  static std::string channel_record(const Channel& c);

  std::FILE* file_{nullptr};
  bool ok_{false};
  std::uint64_t offset_{0};
  std::uint32_t data_crc_{0};
  WriterOptions options_;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<ChunkIndex> chunk_indexes_;
  // The open chunk: its records, message times, and per channel the (log time, offset) of each message.
  std::string chunk_;
  std::uint64_t chunk_start_{0}, chunk_end_{0};
  bool chunk_has_messages_{false};
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::uint64_t message_count_{0}, start_time_{0}, end_time_{0};
};

}  // namespace gyrostab::mcap
