// A shard's records file is trusted only when it is sealed: its last line is the trailer
//   # complete rows=N fnv1a64=HHHHHHHHHHHHHHHH
// where N counts the record rows (the header excluded) and the hash covers every byte before the
// trailer. A file cut short, concatenated, interleaved by two writers or edited by hand fails the
// check, and `run` redoes its shard instead of counting it. Readers of records skip lines that
// start with '#', so readers that skip comment lines read sealed files unchanged.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace ra {

// The trailer line (with its '\n') for `body`, the file's bytes before it, holding `rows` rows.
std::string shard_trailer(std::string_view body, uint64_t rows);

// Appends the trailer to the finished file at `path` (a temporary, before it is committed);
// returns the number of rows. Throws std::runtime_error on I/O failure.
uint64_t seal_shard_file(const std::string& path);

// Empty when the file at `path` is sealed, its trailer matches its contents and it holds
// `expected_rows` rows; otherwise why not ("no trailer (cut short?)", "rows=... but ... expected",
// "hash mismatch", ...).
std::string check_shard_file(const std::string& path, uint64_t expected_rows);

}  // namespace ra
