#include "net_namespace.h"

#include <array>
#include <csignal>
#include <cstdio>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace igi::soak {

int shell(const std::string& command, std::string* output) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::string text;
  std::array<char, 256> buffer{};
  while (fgets(buffer.data(), int(buffer.size()), pipe)) text += buffer.data();
  const int status = pclose(pipe);
  if (output) *output = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::unique_ptr<NetNamespace> NetNamespace::create(std::string& why_not) {
  if (geteuid() != 0) {
    why_not = "not root (ip netns needs CAP_SYS_ADMIN and CAP_NET_ADMIN)";
    return nullptr;
  }
  std::string out;
  if (shell("ip -V", &out) != 0) {
    why_not = "no iproute2 'ip' command";
    return nullptr;
  }
  const int pid = int(getpid());
  std::unique_ptr<NetNamespace> ns(new NetNamespace);
  ns->name_ = "igi-soak-" + std::to_string(pid);
  ns->host_link_ = "igis" + std::to_string(pid) + "h";
  ns->ns_link_ = "igis" + std::to_string(pid) + "n";
  // A /30 of 10.200.0.0/13 chosen by pid, so concurrent runs do not collide.
  const std::string net = "10." + std::to_string(200 + (pid >> 14) % 8) + "." + std::to_string((pid >> 6) % 256) + ".";
  const int base = (pid % 64) * 4;
  ns->host_address_ = net + std::to_string(base + 1);
  ns->ns_address_ = net + std::to_string(base + 2);
  const std::string steps[] = {
      "ip netns add " + ns->name_,
      "ip link add " + ns->host_link_ + " type veth peer name " + ns->ns_link_,
      "ip link set " + ns->ns_link_ + " netns " + ns->name_,
      "ip addr add " + ns->host_address_ + "/30 dev " + ns->host_link_,
      "ip link set " + ns->host_link_ + " up",
      "ip netns exec " + ns->name_ + " ip addr add " + ns->ns_address_ + "/30 dev " + ns->ns_link_,
      "ip netns exec " + ns->name_ + " ip link set " + ns->ns_link_ + " up",
      "ip netns exec " + ns->name_ + " ip link set lo up",
  };
  for (const std::string& step : steps)
    if (shell(step, &out) != 0) {
      why_not = "'" + step + "' failed: " + out.substr(0, out.find('\n'));
      return nullptr;  // the destructor removes what was made
    }
  return ns;
}

NetNamespace::~NetNamespace() {
  shell("ip link del " + host_link_);  // takes its peer with it
  shell("ip netns del " + name_);
}

bool NetNamespace::cut() { return shell("ip link set " + host_link_ + " down") == 0; }
bool NetNamespace::restore() { return shell("ip link set " + host_link_ + " up") == 0; }

void remove_stale_namespaces() {
  std::string list;
  if (shell("ip netns list", &list) != 0) return;
  std::istringstream lines(list);
  for (std::string name; lines >> name;) {
    if (name.rfind("igi-soak-", 0) != 0) continue;
    const int pid = std::atoi(name.c_str() + 9);
    if (pid <= 0 || kill(pid, 0) == 0) continue;  // its driver still runs
    shell("ip link del igis" + std::to_string(pid) + "h");
    shell("ip netns del " + name);
  }
}

}  // namespace igi::soak
