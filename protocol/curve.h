#pragma once
// ZeroMQ CURVE keys and their files, and which endpoints need them.
//
// A key is 32 bytes written as 40 characters of Z85. igi-keys writes, in the
// text layout of czmq's zcert (so zcert and pyzmq certificates parse too,
// though those name their files differently: pyzmq's public one is NAME.key):
//   NAME.key   public-key = "..." and secret-key = "...", mode 0600: stays on its machine
//   NAME.pub   public-key = "..." only: give it to the other side
// Every reader throws std::runtime_error naming the file (and line) and what
// was expected: missing, malformed, a secret readable by other users, a
// public key that does not belong to the secret one.
#include <map>
#include <string>
#include <vector>

#include <zmq.hpp>

namespace igi::protocol {

struct CurveKeyPair {
  std::string public_key;  // Z85
  std::string secret_key;  // Z85
};

// What a CURVE client (a worker) needs: the server's public key and its own pair.
struct CurveClientKeys {
  std::string server_key;
  CurveKeyPair own;
};

// What a CURVE server (the master) needs: its pair and who may connect.
struct CurveServerKeys {
  CurveKeyPair own;
  std::map<std::string, std::string> authorized;  // Z85 public key -> a name for logs
};

CurveKeyPair make_curve_keypair();
// 40 characters of the Z85 alphabet that decode to 32 bytes.
bool is_z85_key(const std::string& text);
std::string z85_encode_key(const uint8_t bytes[32]);

// Writes NAME.key (0600) and NAME.pub; refuses to overwrite either.
void write_key_files(const std::string& name, const CurveKeyPair& keys);
// A secret key file: only its owner may read it, and its public key must match.
CurveKeyPair read_secret_key_file(const std::string& path);
// A public key file; one holding a secret key is refused (give NAME.pub).
std::string read_public_key_file(const std::string& path);
// A folder: every *.pub file in it. A file: a .pub file, or a list with one
// Z85 key per line, optionally followed by a name; lines starting '#' are comments.
std::map<std::string, std::string> read_authorized_keys(const std::string& path);

// The same "name = value" text as the files, for keys passed without a file
// (igi-master to its local workers through a pipe): public-key, secret-key, server-key.
std::string format_client_keys(const CurveClientKeys& keys);
CurveClientKeys parse_client_keys(const std::string& text, const std::string& source);

// Whether a bind endpoint can be reached only from this machine: tcp on
// 127.0.0.0/8, localhost, ::1 or lo; ipc; inproc. Anything else is a network.
bool is_local_endpoint(const std::string& endpoint);

// Socket options, set before bind/connect. The server also names a ZAP
// domain, so that libzmq asks the ZAP handler (zap.h) about every client.
void make_curve_server(zmq::socket_t& socket, const CurveKeyPair& own);
void make_curve_client(zmq::socket_t& socket, const CurveClientKeys& keys);

}  // namespace igi::protocol
