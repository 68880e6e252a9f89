#pragma once
// Whole files as bytes, read and written in one piece.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace igi {

// The whole of a regular file, read by its size; nullopt when it is not a
// regular file or cannot be read.
std::optional<std::vector<uint8_t>> read_file_bytes(const std::string& path);

// Whether `path`, links and ".." resolved, lies inside the folder `root`
// (itself resolved by the caller: std::filesystem::weakly_canonical). An
// empty root holds nothing. Scenes read external files only from their own folder.
bool inside_folder(const std::string& root, const std::string& path);

// Whether the process's umask may narrow a new file's permissions: a key file
// must get exactly its mode (owner read/write), a cached scene no wider than
// the user's umask allows.
enum class Umask { applies, ignored };

// Creates `path` with permissions `mode` and writes all of `size` bytes. Fails
// if anything is at `path` already: it never overwrites a file and never
// writes through a link someone left there. Throws std::runtime_error naming
// the path and the reason.
void write_new_file(const std::string& path, const void* data, size_t size, unsigned mode, Umask umask);

}  // namespace igi
