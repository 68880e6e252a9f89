#pragma once
// A network namespace joined to this one by a veth pair, for a worker whose
// link can be cut (ip link set ... down) and restored. Needs root (or
// CAP_NET_ADMIN) and iproute2; create() says why not when it cannot.
// The namespace and the link go when the object goes; namespaces left by a
// driver that was killed are removed by the next run (remove_stale_namespaces).
#include <memory>
#include <string>
#include <vector>

namespace igi::soak {

class NetNamespace {
 public:
  static std::unique_ptr<NetNamespace> create(std::string& why_not);
  ~NetNamespace();
  NetNamespace(const NetNamespace&) = delete;
  NetNamespace& operator=(const NetNamespace&) = delete;

  // This side's address: the master listens here, the namespace's worker connects to it.
  const std::string& host_address() const { return host_address_; }
  // Prepended to a command to run it inside the namespace (ip netns exec execs it: same pid).
  std::vector<std::string> exec_prefix() const { return {"ip", "netns", "exec", name_}; }
  bool cut();
  bool restore();

 private:
  NetNamespace() = default;
  std::string name_, host_link_, ns_link_, host_address_, ns_address_;
};

void remove_stale_namespaces();
// Runs a shell command; returns its exit status, its output in `output`.
int shell(const std::string& command, std::string* output = nullptr);

}  // namespace igi::soak
