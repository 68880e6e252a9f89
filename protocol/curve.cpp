#include "protocol/curve.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

#include "io/file_bytes.h"

namespace igi::protocol {
namespace {

namespace fs = std::filesystem;
constexpr size_t kZ85KeyLength = 40;
constexpr size_t kMaxKeyFileBytes = 64 * 1024;  // a key file is a few hundred bytes

std::string trim(const std::string& s) {
  const size_t begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

std::string read_text(const std::string& path, const char* what) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw std::runtime_error(path + ": a folder, expected " + what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read " + what + " (" + std::strerror(errno) + ")");
  std::string text(kMaxKeyFileBytes + 1, '\0');
  in.read(text.data(), std::streamsize(text.size()));
  text.resize(size_t(in.gcount()));
  if (text.size() > kMaxKeyFileBytes) throw std::runtime_error(path + ": over 64 KiB, not " + what);
  return text;
}

// The key lines of a zcert-style file: `public-key = "Z85"` and the like.
// Other "name = value" lines (zcert metadata) and section names are skipped.
struct KeyFields {
  std::map<std::string, std::string> values;  // public-key, secret-key, server-key
};

KeyFields parse_fields(const std::string& text, const std::string& source) {
  KeyFields fields;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    line = trim(line);
    const size_t equals = line.find('=');
    if (line.empty() || line[0] == '#' || equals == std::string::npos) continue;
    const std::string name = trim(line.substr(0, equals));
    if (name != "public-key" && name != "secret-key" && name != "server-key") continue;
    std::string value = trim(line.substr(equals + 1));
    if (value.size() >= 2 && value.front() == '"' && value.back() == '"') value = value.substr(1, value.size() - 2);
    const std::string where = source + ":" + std::to_string(number) + ": " + name;
    if (fields.values.count(name)) throw std::runtime_error(where + " given twice");
    if (!is_z85_key(value))  // never echo the value: it may be a secret
      throw std::runtime_error(where + ": expected 40 characters of Z85 in quotes, got " +
                               std::to_string(value.size()) + " characters" +
                               (value.size() == kZ85KeyLength ? " outside the Z85 alphabet" : ""));
    fields.values[name] = value;
  }
  return fields;
}

std::string public_of(const std::string& secret_key) {
  char public_key[kZ85KeyLength + 1];
  if (zmq_curve_public(public_key, secret_key.c_str()) != 0)
    throw std::runtime_error(std::string("cannot derive a CURVE public key: ") + zmq_strerror(zmq_errno()));
  return public_key;
}

// Creates `path` with exactly `mode`, failing if it exists (never overwrites a key).
void write_key_file(const std::string& path, const std::string& text, mode_t mode) {
  write_new_file(path, text.data(), text.size(), mode, Umask::ignored);
}

std::string certificate(const char* kind, const std::string& lines) {
  return std::string("#   ZeroMQ CURVE ") + kind + " Certificate, made by igi-keys (zcert layout)\n" + lines;
}

}  // namespace

CurveKeyPair make_curve_keypair() {
  char public_key[kZ85KeyLength + 1], secret_key[kZ85KeyLength + 1];
  if (zmq_curve_keypair(public_key, secret_key) != 0)
    throw std::runtime_error(std::string("cannot make a CURVE key pair (is libzmq built with libsodium?): ") +
                             zmq_strerror(zmq_errno()));
  return {public_key, secret_key};
}

bool is_z85_key(const std::string& text) {
  uint8_t bytes[32];
  return text.size() == kZ85KeyLength && zmq_z85_decode(bytes, text.c_str()) != nullptr;
}

std::string z85_encode_key(const uint8_t bytes[32]) {
  char text[kZ85KeyLength + 1];
  zmq_z85_encode(text, bytes, 32);
  return text;
}

void write_key_files(const std::string& name, const CurveKeyPair& keys) {
  const std::string secret_path = name + ".key", public_path = name + ".pub";
  for (const std::string& path : {secret_path, public_path})
    if (fs::exists(fs::symlink_status(path)))
      throw std::runtime_error(path + " exists: not overwritten (remove it or choose another name)");
  write_key_file(secret_path,
                 certificate("**Secret**", "#   Keep it on this machine, readable only by you (mode 0600).\n\n"
                                           "metadata\ncurve\n    public-key = \"" + keys.public_key +
                                           "\"\n    secret-key = \"" + keys.secret_key + "\"\n"),
                 0600);
  write_key_file(public_path,
                 certificate("Public", "#   Give it to the other side: a master's to its workers (--master-key),\n"
                                       "#   a worker's to the master (--authorized-keys).\n\n"
                                       "metadata\ncurve\n    public-key = \"" + keys.public_key + "\"\n"),
                 0644);
}

CurveKeyPair read_secret_key_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && (st.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", unsigned(st.st_mode & 07777));
    throw std::runtime_error(path + ": a secret key open to other users (mode " + mode + "); run chmod 600 " + path);
  }
  const KeyFields fields = parse_fields(read_text(path, "a secret key file"), path);
  if (!fields.values.count("secret-key"))
    throw std::runtime_error(path + ": no secret-key line; expected a NAME.key file made by igi-keys new NAME");
  CurveKeyPair keys{public_of(fields.values.at("secret-key")), fields.values.at("secret-key")};
  auto given = fields.values.find("public-key");
  if (given != fields.values.end() && given->second != keys.public_key)
    throw std::runtime_error(path + ": public-key does not belong to secret-key (the file was edited?)");
  return keys;
}

std::string read_public_key_file(const std::string& path) {
  const KeyFields fields = parse_fields(read_text(path, "a public key file"), path);
  if (fields.values.count("secret-key"))
    throw std::runtime_error(path + ": holds a secret key; give the public file (NAME.pub), and keep NAME.key private");
  if (!fields.values.count("public-key"))
    throw std::runtime_error(path + ": no public-key line; expected a NAME.pub file made by igi-keys new NAME");
  return fields.values.at("public-key");
}

std::map<std::string, std::string> read_authorized_keys(const std::string& path) {
  std::map<std::string, std::string> keys;
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    for (const fs::directory_entry& entry : fs::directory_iterator(path))
      if (entry.path().extension() == ".pub")
        keys[read_public_key_file(entry.path().string())] = entry.path().stem().string();
    return keys;
  }
  if (fs::path(path).extension() == ".pub") {
    keys[read_public_key_file(path)] = fs::path(path).stem().string();
    return keys;
  }
  std::istringstream lines(read_text(path, "a list of public keys"));
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    line = trim(line);
    const std::string key = line.substr(0, line.find_first_of(" \t"));
    const std::string where = path + ":" + std::to_string(number);
    if (is_z85_key(key)) keys[key] = key.size() < line.size() ? trim(line.substr(key.size())) : where;
    else if (!line.empty() && line[0] != '#')
      throw std::runtime_error(where + ": expected a 40-character Z85 public key, optionally followed by a name");
  }
  return keys;
}

std::string format_client_keys(const CurveClientKeys& keys) {
  return "server-key = \"" + keys.server_key + "\"\npublic-key = \"" + keys.own.public_key + "\"\nsecret-key = \"" +
         keys.own.secret_key + "\"\n";
}

CurveClientKeys parse_client_keys(const std::string& text, const std::string& source) {
  const KeyFields fields = parse_fields(text, source);
  for (const char* name : {"server-key", "secret-key"})
    if (!fields.values.count(name)) throw std::runtime_error(source + ": no " + name + " line");
  CurveClientKeys keys;
  keys.server_key = fields.values.at("server-key");
  keys.own.secret_key = fields.values.at("secret-key");
  keys.own.public_key = public_of(keys.own.secret_key);
  return keys;
}

bool is_local_endpoint(const std::string& endpoint) {
  if (endpoint.rfind("ipc://", 0) == 0 || endpoint.rfind("inproc://", 0) == 0) return true;
  if (endpoint.rfind("tcp://", 0) != 0) return false;
  const std::string address = endpoint.substr(6);  // HOST:PORT
  std::string host = address.substr(0, address.rfind(':'));
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  if (host == "localhost" || host == "::1" || host == "lo") return true;
  // 127.0.0.0/8, written as four numbers.
  unsigned a = 0, b = 0, c = 0, d = 0;
  char rest = 0;
  return std::sscanf(host.c_str(), "%u.%u.%u.%u%c", &a, &b, &c, &d, &rest) == 4 && a == 127 && b < 256 && c < 256 &&
         d < 256;
}

void make_curve_server(zmq::socket_t& socket, const CurveKeyPair& own) {
  socket.set(zmq::sockopt::curve_server, true);
  socket.set(zmq::sockopt::curve_secretkey, own.secret_key);
  socket.set(zmq::sockopt::zap_domain, "igi");
}

void make_curve_client(zmq::socket_t& socket, const CurveClientKeys& keys) {
  socket.set(zmq::sockopt::curve_serverkey, keys.server_key);
  socket.set(zmq::sockopt::curve_publickey, keys.own.public_key);
  socket.set(zmq::sockopt::curve_secretkey, keys.own.secret_key);
}

}  // namespace igi::protocol
