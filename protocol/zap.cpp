#include "protocol/zap.h"

#include "protocol/curve.h"
#include "protocol/socket.h"

namespace igi::protocol {

ZapHandler::ZapHandler(zmq::context_t& context, std::map<std::string, std::string> authorized)
    : authorized_(std::move(authorized)), socket_(context, zmq::socket_type::rep) {
  configure(socket_);
  socket_.bind(kZapEndpoint);
}

std::vector<ZapDecision> ZapHandler::answer_waiting() {
  std::vector<ZapDecision> decisions;
  for (;;) {
    std::vector<zmq::message_t> request;
    bool more = true;
    while (more) {
      zmq::message_t part;
      if (!socket_.recv(part, zmq::recv_flags::dontwait)) break;
      more = part.more();
      if (request.size() < 8) request.push_back(std::move(part));  // RFC 27 has at most 7 frames for CURVE
    }
    if (request.empty()) return decisions;
    decisions.push_back(answer(request));
  }
}

// Request: version, request id, domain, address, routing id, mechanism, credentials...
// Reply:   version, request id, status code, status text, user id, metadata.
ZapDecision ZapHandler::answer(std::vector<zmq::message_t>& request) {
  ZapDecision d;
  std::string status = "400", text = "unknown CURVE public key";
  const bool curve = request.size() == 7 && request[0].to_string() == "1.0" && request[5].to_string() == "CURVE" &&
                     request[6].size() == 32;
  if (request.size() >= 4) d.address = request[3].to_string();
  if (!curve) {
    text = "only CURVE clients are served";
  } else {
    d.public_key = z85_encode_key(request[6].data<uint8_t>());
    if (auto it = authorized_.find(d.public_key); it != authorized_.end()) {
      d.name = it->second;
      if (quarantined_.count(d.name)) {
        d.quarantined = true;
        text = "this key was quarantined by the master";
      } else {
        d.allowed = true;
        status = "200", text = "OK";
      }
    }
  }
  const std::string request_id = request.size() >= 2 ? request[1].to_string() : "";
  socket_.send(zmq::buffer(std::string("1.0")), zmq::send_flags::sndmore);
  socket_.send(zmq::buffer(request_id), zmq::send_flags::sndmore);
  socket_.send(zmq::buffer(status), zmq::send_flags::sndmore);
  socket_.send(zmq::buffer(text), zmq::send_flags::sndmore);
  socket_.send(zmq::buffer(d.allowed ? d.name : std::string()), zmq::send_flags::sndmore);  // user id: the message property "User-Id"
  socket_.send(zmq::buffer(std::string()), zmq::send_flags::none);
  return d;
}

}  // namespace igi::protocol
