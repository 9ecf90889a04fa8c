#include "http_guard.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <functional>
#include <thread>
#include <vector>

namespace ballsrv {

namespace {

using SteadyClock = std::chrono::steady_clock;

double seconds_until(SteadyClock::time_point t) { return std::chrono::duration<double>(t - SteadyClock::now()).count(); }

// Whether sock has something to read (or was closed) within seconds.
bool readable_within(socket_t sock, double seconds) {
  pollfd p{sock, POLLIN, 0};
  int ms = static_cast<int>(std::max(0.0, seconds) * 1000.0);
  return ::poll(&p, 1, ms) > 0;
}

std::string address_of(socket_t sock, int *port) {
  sockaddr_storage a{};
  socklen_t len = sizeof(a);
  char text[INET6_ADDRSTRLEN] = "";
  *port = 0;
  if (::getpeername(sock, reinterpret_cast<sockaddr *>(&a), &len) != 0) return "";
  if (a.ss_family == AF_INET) {
    const auto *v4 = reinterpret_cast<const sockaddr_in *>(&a);
    ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof(text));
    *port = ntohs(v4->sin_port);
  } else if (a.ss_family == AF_INET6) {
    const auto *v6 = reinterpret_cast<const sockaddr_in6 *>(&a);
    ::inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof(text));
    *port = ntohs(v6->sin6_port);
  }
  return text;
}

// One request's stream: its reads end at the head's deadline and after its
// byte budget; what is past them reads as a broken connection, which
// cpp-httplib answers 400 or drops.
class GuardedStream : public httplib::Stream {
 public:
  GuardedStream(socket_t sock, const std::string &address, int port, SteadyClock::time_point deadline, size_t budget,
                const HttpLimits &limits)
      : sock_(sock), address_(address), port_(port), deadline_(deadline), budget_(budget), limits_(limits) {}

  bool is_readable() const override { return off_ < len_ || readable_within(sock_, seconds_until(deadline_)); }
  bool is_writable() const override {
    pollfd p{sock_, POLLOUT, 0};
    return ::poll(&p, 1, static_cast<int>(limits_.head_seconds * 1000.0)) > 0 && !(p.revents & (POLLERR | POLLHUP));
  }
  ssize_t read(char *ptr, size_t size) override {
    if (off_ == len_) {
      if (read_ >= budget_) {
        large = true;
        return -1;
      }
      if (SteadyClock::now() >= deadline_ || !readable_within(sock_, seconds_until(deadline_))) {
        late = true;
        return -1;
      }
      ssize_t n = ::recv(sock_, buffer_, std::min(sizeof(buffer_), budget_ - read_), 0);
      if (n <= 0) return n;
      off_ = 0;
      len_ = static_cast<size_t>(n);
      read_ += len_;
    }
    size_t n = std::min(size, len_ - off_);
    std::memcpy(ptr, buffer_ + off_, n);
    off_ += n;
    return static_cast<ssize_t>(n);
  }
  ssize_t write(const char *ptr, size_t size) override {
    if (!is_writable()) return -1;
    return ::send(sock_, ptr, size, MSG_NOSIGNAL);
  }
  void get_remote_ip_and_port(std::string &ip, int &port) const override {
    ip = address_;
    port = port_;
  }
  void get_local_ip_and_port(std::string &ip, int &port) const override {
    sockaddr_storage a{};
    socklen_t len = sizeof(a);
    char text[INET6_ADDRSTRLEN] = "";
    port = 0;
    if (::getsockname(sock_, reinterpret_cast<sockaddr *>(&a), &len) == 0 && a.ss_family == AF_INET) {
      const auto *v4 = reinterpret_cast<const sockaddr_in *>(&a);
      ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof(text));
      port = ntohs(v4->sin_port);
    }
    ip = text;
  }
  socket_t socket() const override { return sock_; }

  bool late = false, large = false;  // the head came after its deadline, or went past its budget

 private:
  socket_t sock_;
  std::string address_;
  int port_;
  SteadyClock::time_point deadline_;
  size_t budget_;
  const HttpLimits &limits_;
  char buffer_[4096];
  size_t off_ = 0, len_ = 0, read_ = 0;
};

thread_local bool t_shed = false;  // the connection being served is one the queue had no room for

// cpp-httplib's thread pool with a bounded queue: a connection that finds it
// full is closed at once, on the accepting thread.
class BoundedPool : public httplib::TaskQueue {
 public:
  BoundedPool(int threads, int queue) : queue_(static_cast<size_t>(queue)) {
    for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { work(); });
  }
  void enqueue(std::function<void()> fn) override {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (jobs_.size() < queue_) {
        jobs_.push_back(std::move(fn));
        ready_.notify_one();
        return;
      }
    }
    t_shed = true;
    fn();  // (GuardedHttp closes it)
    t_shed = false;
  }
  void shutdown() override {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    ready_.notify_all();
    for (auto &t : threads_) t.join();
  }

 private:
  void work() {
    for (;;) {
      std::function<void()> fn;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        ready_.wait(lock, [&] { return stopping_ || !jobs_.empty(); });
        if (jobs_.empty()) return;  // (stopping, nothing left)
        fn = std::move(jobs_.front());
        jobs_.pop_front();
      }
      fn();
    }
  }
  size_t queue_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<std::function<void()>> jobs_;
  std::vector<std::thread> threads_;
  bool stopping_ = false;
};

}  // namespace

GuardedHttp::GuardedHttp(const HttpLimits &limits, int threads) : limits_(limits) {
  new_task_queue = [this, threads] { return new BoundedPool(threads, limits_.queue); };
  set_payload_max_length(limits_.head_bytes);
  set_pre_routing_handler([this](const httplib::Request &req, httplib::Response &res) {
    if (req.headers.size() <= limits_.headers) return HandlerResponse::Unhandled;
    refusals_.too_many_headers++;
    res.status = 431;
    res.set_content("too many header lines\n", "text/plain");
    return HandlerResponse::Handled;
  });
}

void GuardedHttp::widen_backlog() {
  socket_t s = svr_sock_;
  if (s != INVALID_SOCKET) ::listen(s, std::max(limits_.queue, 5));
}

bool GuardedHttp::admit(const std::string &address) {
  if (!limits_.proxy.empty() && address == limits_.proxy) return true;  // (its clients' shares are the proxy's to keep)
  std::lock_guard<std::mutex> lock(mutex_);
  int &n = open_[address];
  if (n >= limits_.per_address) {
    if (n == 0) open_.erase(address);
    return false;
  }
  n++;
  return true;
}

void GuardedHttp::release(const std::string &address) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = open_.find(address);
  if (it != open_.end() && --it->second <= 0) open_.erase(it);  // (nothing kept of an address gone)
}

// cpp-httplib's keep-alive loop (process_server_socket) with the guard's
// limits: an address over its share and a connection the queue had no room
// for are closed unread; each request gets a fresh deadline and budget.
bool GuardedHttp::process_and_close_socket(socket_t sock) {
  int port = 0;
  std::string address = address_of(sock, &port);
  bool served = false;
  if (t_shed) {
    refusals_.queue_full++;
  } else if (!admit(address)) {
    refusals_.per_address++;
  } else {
    served = true;
    for (size_t left = keep_alive_max_count_; left > 0 && svr_sock_ != INVALID_SOCKET; --left) {
      if (!readable_within(sock, limits_.idle_seconds)) break;
      auto deadline = SteadyClock::now() + std::chrono::duration_cast<SteadyClock::duration>(
                                         std::chrono::duration<double>(limits_.head_seconds));
      GuardedStream strm(sock, address, port, deadline, limits_.head_bytes, limits_);
      bool closed = false;
      bool ok = process_request(strm, left == 1, closed, nullptr);
      refusals_.head_late += strm.late;
      refusals_.head_large += strm.large;
      if (!ok || closed || strm.late || strm.large) break;
    }
    release(address);
  }
  ::shutdown(sock, SHUT_RDWR);
  ::close(sock);
  return served;
}

}  // namespace ballsrv
