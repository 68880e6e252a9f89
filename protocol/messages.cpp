#include "protocol/messages.h"

namespace igi::protocol {

const char* message_name(MessageType type) {
  switch (type) {
    case MessageType::Hello: return "Hello";
    case MessageType::Welcome: return "Welcome";
    case MessageType::Refuse: return "Refuse";
    case MessageType::SceneRequest: return "SceneRequest";
    case MessageType::SceneData: return "SceneData";
    case MessageType::FrameSetup: return "FrameSetup";
    case MessageType::TileJob: return "TileJob";
    case MessageType::TileResult: return "TileResult";
    case MessageType::Heartbeat: return "Heartbeat";
    case MessageType::Bye: return "Bye";
    case MessageType::CancelFrame: return "CancelFrame";
  }
  return "Unknown";
}

const char* pixel_codec_name(PixelCodec codec) {
  switch (codec) {
    case PixelCodec::Raw: return "raw";
    case PixelCodec::Zstd: return "zstd";
    case PixelCodec::Lz4: return "lz4";
  }
  return "unknown";
}

namespace {
struct TypeOf {
  MessageType operator()(const Hello&) const { return MessageType::Hello; }
  MessageType operator()(const Welcome&) const { return MessageType::Welcome; }
  MessageType operator()(const Refuse&) const { return MessageType::Refuse; }
  MessageType operator()(const SceneRequest&) const { return MessageType::SceneRequest; }
  MessageType operator()(const SceneData&) const { return MessageType::SceneData; }
  MessageType operator()(const FrameSetupMsg&) const { return MessageType::FrameSetup; }
  MessageType operator()(const TileJobMsg&) const { return MessageType::TileJob; }
  MessageType operator()(const TileResult&) const { return MessageType::TileResult; }
  MessageType operator()(const Heartbeat&) const { return MessageType::Heartbeat; }
  MessageType operator()(const Bye&) const { return MessageType::Bye; }
  MessageType operator()(const CancelFrame&) const { return MessageType::CancelFrame; }
};
}  // namespace

MessageType type_of(const Message& message) { return std::visit(TypeOf{}, message); }

}  // namespace igi::protocol
