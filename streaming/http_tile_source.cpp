// HttpTileSource (http_tile_source.h): one long-running I/O task, one libcurl multi handle.
//
// Threads: callers of start()/cancel()/readText() append Commands under `mutex` and wake the
// I/O task; everything curl-related and every Transfer is touched by the I/O task only (or by
// the destructor when the runner never started the task).
// `mutex` also guards the counters and the set of live request ids, which any thread may read.

#include "streaming/http_tile_source.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <chrono>
#include <future>
#include <map>
#include <condition_variable>
#include <mutex>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <curl/curl.h>

#include "datasets/http_retry_policy.h"
#include "streaming/disk_tile_cache.h"

namespace vegstream::streaming {
namespace {
using datasets::AttemptEnd;
using datasets::AttemptVerdict;
using datasets::backoffDelayMs;
using datasets::describeAttempt;
using datasets::judgeAttempt;

constexpr curl_off_t kMaxBodyBytes = 256ll << 20;  // no tile is this large: a server gone wrong
constexpr long kIdlePollMs = 1000;                 // upper bound of one curl_multi_poll wait

void initCurlOnce() {
  static std::once_flag once;
  std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
}

// One request from start() to its callback, across all its attempts.
struct Transfer {
  uint64_t seq = 0;  // start order: queued transfers launch in this order
  RequestId id = 0;
  bool isTile = true;  // start()ed (counted, cancellable, cached) or readText()'s
  std::string url;
  std::string cacheKey;  // the URL without its scheme
  FetchCallback done;
  int attempts = 0;
  double notBeforeS = 0.0;  // back-off: not launched again before this (clock seconds)
  CURL* easy = nullptr;     // non-null while running
  std::vector<uint8_t> body;
  char errorBuffer[CURL_ERROR_SIZE] = {};
  std::string lastProblem;
};

struct Command {
  std::unique_ptr<Transfer> start;  // null: cancel `cancelId`
  RequestId cancelId = 0;
};

size_t appendBody(char* data, size_t size, size_t count, void* user) {
  auto* t = static_cast<Transfer*>(user);
  t->body.insert(t->body.end(), reinterpret_cast<uint8_t*>(data), reinterpret_cast<uint8_t*>(data) + size * count);
  return size * count;
}

std::string percentEncodePath(const std::string& path) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (char c : path) {
    const auto u = static_cast<unsigned char>(c);
    const bool keep = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' ||
                      c == '.' || c == '_' || c == '~' || c == '/';
    if (keep) {
      out += c;
    } else {
      out += '%';
      out += hex[u >> 4];
      out += hex[u & 15];
    }
  }
  return out;
}

}  // namespace

Status checkHttpUrl(const std::string& url) {
  initCurlOnce();
  CURLU* u = curl_url();
  const CURLUcode rc = curl_url_set(u, CURLUPART_URL, url.c_str(), 0);
  char* scheme = nullptr;
  char* host = nullptr;
  bool good = rc == CURLUE_OK && curl_url_get(u, CURLUPART_SCHEME, &scheme, 0) == CURLUE_OK &&
              curl_url_get(u, CURLUPART_HOST, &host, 0) == CURLUE_OK;
  if (good) good = (std::string(scheme) == "http" || std::string(scheme) == "https") && host[0] != '\0';
  curl_free(scheme);
  curl_free(host);
  curl_url_cleanup(u);
  if (!good) return makeError(ErrorKind::InvalidInput, "'" + url + "' is not an http:// or https:// URL with a host");
  return {};
}

struct HttpTileSource::Impl {
  enum class Loop { NotStarted, Running, Done };
  HttpSourceOptions opt;
  SteadyClock ownClock;
  const Clock* clock = &ownClock;
  std::string base;  // baseUrl ending in '/'
  std::unique_ptr<DiskTileCache> cache;
  Logger log;
  CURLM* multi = nullptr;

  // Shared with callers, under `mutex`.
  mutable std::mutex mutex;
  std::vector<Command> commands;
  bool stopping = false;
  uint64_t nextSeq = 0;
  std::unordered_set<RequestId> live;  // started tiles not yet called back
  SourceCounters counters;
  HttpTransportStats transport;

  // I/O thread only.
  std::map<uint64_t, std::unique_ptr<Transfer>> transfers;  // by seq: queued, backing off, running
  std::unordered_map<RequestId, uint64_t> seqOfTile;
  size_t running = 0;
  Loop loop = Loop::NotStarted;  // under `mutex`
  std::condition_variable loopDone;

  // The I/O task, or the destructor when the task never started: runs run() once.
  void runOnce() {
    {
      std::lock_guard lock(mutex);
      if (loop != Loop::NotStarted) return;
      loop = Loop::Running;
    }
    run();
    std::lock_guard lock(mutex);
    loop = Loop::Done;
    loopDone.notify_all();
  }

  // Queues a command for the I/O thread and wakes it. A tile start also becomes live and
  // counted in the same critical section, so a cancel() after start() always follows it.
  void post(Command c) {
    {
      std::lock_guard lock(mutex);
      if (c.start) {
        c.start->seq = nextSeq++;
        if (c.start->isTile) {
          const bool fresh = live.insert(c.start->id).second;
          assert(fresh && "start() with the id of a request still in flight");
          (void)fresh;
          ++counters.requestsStarted;
        }
      }
      commands.push_back(std::move(c));
    }
    curl_multi_wakeup(multi);
  }

  void run();
  bool takeCommands();
  void accept(std::unique_ptr<Transfer> t);
  void launchReady(double nowS);
  void launch(Transfer& t);
  void drainFinished();
  void endAttempt(Transfer& t, CURLcode code);
  void stopRunning(Transfer& t);
  void complete(uint64_t seq, FetchOutcome outcome, std::string message);
  long pollTimeoutMs(double nowS) const;
};

void HttpTileSource::Impl::run() {
  for (;;) {
    if (!takeCommands()) break;
    launchReady(clock->nowS());
    int stillRunning = 0;
    curl_multi_perform(multi, &stillRunning);
    drainFinished();
    launchReady(clock->nowS());  // slots freed and back-offs ended: a new timer makes the poll short
    curl_multi_poll(multi, nullptr, 0, static_cast<int>(pollTimeoutMs(clock->nowS())), nullptr);
  }
  // Stopping: whatever is left ends Cancelled, in start order.
  while (!transfers.empty()) complete(transfers.begin()->first, FetchOutcome::Cancelled, "the source was closed");
}

// Applies queued commands in the order they were made; false once the source is stopping.
bool HttpTileSource::Impl::takeCommands() {
  std::vector<Command> batch;
  bool stop = false;
  {
    std::lock_guard lock(mutex);
    batch.swap(commands);
    stop = stopping;
  }
  for (Command& c : batch) {
    if (c.start) {
      accept(std::move(c.start));
      continue;
    }
    auto it = seqOfTile.find(c.cancelId);
    if (it == seqOfTile.end()) continue;  // already called back: nothing to cancel
    complete(it->second, FetchOutcome::Cancelled, "cancelled");
  }
  return !stop;
}

void HttpTileSource::Impl::accept(std::unique_ptr<Transfer> t) {
  const uint64_t seq = t->seq;
  const bool isTile = t->isTile;
  if (isTile) seqOfTile[t->id] = seq;
  std::optional<std::vector<uint8_t>> cached;
  if (isTile && cache) cached = cache->get(t->cacheKey);
  transfers.emplace(seq, std::move(t));
  if (cached) {
    transfers[seq]->body = std::move(*cached);
    complete(seq, FetchOutcome::Ok, {});
  }
}

void HttpTileSource::Impl::launchReady(double nowS) {
  for (auto& [seq, t] : transfers) {
    if (running >= static_cast<size_t>(opt.maxInFlight)) return;
    if (t->easy == nullptr && t->notBeforeS <= nowS) launch(*t);
  }
}

void HttpTileSource::Impl::launch(Transfer& t) {
  CURL* e = curl_easy_init();
  assert(e != nullptr);
  t.body.clear();
  t.errorBuffer[0] = '\0';
  curl_easy_setopt(e, CURLOPT_URL, t.url.c_str());
  curl_easy_setopt(e, CURLOPT_PRIVATE, &t);
  curl_easy_setopt(e, CURLOPT_WRITEFUNCTION, appendBody);
  curl_easy_setopt(e, CURLOPT_WRITEDATA, &t);
  curl_easy_setopt(e, CURLOPT_ERRORBUFFER, t.errorBuffer);
  curl_easy_setopt(e, CURLOPT_NOSIGNAL, 1L);
  curl_easy_setopt(e, CURLOPT_CONNECTTIMEOUT_MS, opt.connectTimeoutMs);
  curl_easy_setopt(e, CURLOPT_TIMEOUT_MS, opt.totalTimeoutMs);
  curl_easy_setopt(e, CURLOPT_FOLLOWLOCATION, 1L);
  curl_easy_setopt(e, CURLOPT_MAXREDIRS, 5L);
  curl_easy_setopt(e, CURLOPT_MAXFILESIZE_LARGE, kMaxBodyBytes);
  curl_easy_setopt(e, CURLOPT_HTTP_VERSION, static_cast<long>(CURL_HTTP_VERSION_2TLS));
  // Over TLS, wait for ALPN to say whether the connection being set up multiplexes (HTTP/2)
  // rather than opening another. Never over plain http: HTTP/1.1 is known only once the first
  // answer arrives, and every other transfer would wait for it.
  if (t.url.rfind("https://", 0) == 0) curl_easy_setopt(e, CURLOPT_PIPEWAIT, 1L);
  curl_easy_setopt(e, CURLOPT_TCP_KEEPALIVE, 1L);
  curl_easy_setopt(e, CURLOPT_USERAGENT, "vegstream");
  t.easy = e;
  ++t.attempts;
  ++running;
  curl_multi_add_handle(multi, e);
  std::lock_guard lock(mutex);
  ++transport.attempts;
}

void HttpTileSource::Impl::drainFinished() {
  int left = 0;
  while (CURLMsg* m = curl_multi_info_read(multi, &left)) {
    if (m->msg != CURLMSG_DONE) continue;
    Transfer* t = nullptr;
    curl_easy_getinfo(m->easy_handle, CURLINFO_PRIVATE, &t);
    endAttempt(*t, m->data.result);
  }
}

void HttpTileSource::Impl::endAttempt(Transfer& t, CURLcode code) {
  AttemptEnd end;
  end.code = code;
  curl_easy_getinfo(t.easy, CURLINFO_RESPONSE_CODE, &end.httpStatus);
  curl_off_t length = -1;
  curl_easy_getinfo(t.easy, CURLINFO_CONTENT_LENGTH_DOWNLOAD_T, &length);
  end.contentLength = length;
  end.bodyBytes = t.body.size();
  t.lastProblem = describeAttempt(end, t.errorBuffer);
  stopRunning(t);

  const AttemptVerdict verdict = judgeAttempt(end);
  if (verdict == AttemptVerdict::Ok) {
    if (t.isTile && cache) {
      if (Status s = cache->put(t.cacheKey, t.body); !s) log->warn("tile cache: {}", s.error().message);
    }
    complete(t.seq, FetchOutcome::Ok, {});
  } else if (verdict == AttemptVerdict::Missing) {
    complete(t.seq, FetchOutcome::Missing, "GET " + t.url + ": " + t.lastProblem);
  } else if (verdict == AttemptVerdict::Retry && t.attempts < opt.maxAttempts) {
    const long delay = backoffDelayMs(t.attempts + 1, t.seq, opt.backoffBaseMs, opt.backoffMaxMs);
    log->debug("GET {}: {}; attempt {} in {} ms", t.url, t.lastProblem, t.attempts + 1, delay);
    t.notBeforeS = clock->nowS() + static_cast<double>(delay) / 1000.0;
    if (t.isTile) {
      std::lock_guard lock(mutex);
      ++counters.retries;
    }
  } else {
    complete(t.seq, FetchOutcome::Failed,
             "GET " + t.url + ": " + t.lastProblem + " (" + std::to_string(t.attempts) + " attempts)");
  }
}

void HttpTileSource::Impl::stopRunning(Transfer& t) {
  if (t.easy == nullptr) return;
  long connects = 0;
  curl_easy_getinfo(t.easy, CURLINFO_NUM_CONNECTS, &connects);
  curl_multi_remove_handle(multi, t.easy);
  curl_easy_cleanup(t.easy);
  t.easy = nullptr;
  --running;
  std::lock_guard lock(mutex);
  transport.connectionsOpened += static_cast<uint64_t>(connects);
}

void HttpTileSource::Impl::complete(uint64_t seq, FetchOutcome outcome, std::string message) {
  auto node = transfers.extract(seq);
  assert(!node.empty());
  std::unique_ptr<Transfer> t = std::move(node.mapped());
  stopRunning(*t);
  FetchResult r;
  r.id = t->id;
  r.outcome = outcome;
  r.message = std::move(message);
  r.attempts = t->attempts;
  r.fromCache = outcome == FetchOutcome::Ok && t->attempts == 0;
  if (outcome == FetchOutcome::Ok) r.bytes = std::move(t->body);
  if (outcome == FetchOutcome::Missing || outcome == FetchOutcome::Failed) log->debug("{}", r.message);
  if (t->isTile) {
    seqOfTile.erase(t->id);
    std::lock_guard lock(mutex);
    live.erase(t->id);
    switch (outcome) {
      case FetchOutcome::Ok:
        ++counters.requestsCompleted;
        counters.bytesRead += r.bytes.size();
        break;
      case FetchOutcome::Missing: ++counters.requestsMissing; break;
      case FetchOutcome::Failed: ++counters.requestsFailed; break;
      case FetchOutcome::Cancelled: ++counters.requestsCancelled; break;
    }
    if (r.fromCache) ++counters.cacheHits;
  }
  t->done(std::move(r));
}

long HttpTileSource::Impl::pollTimeoutMs(double nowS) const {
  long timeout = kIdlePollMs;
  long curlTimeout = -1;
  curl_multi_timeout(multi, &curlTimeout);
  if (curlTimeout >= 0) timeout = std::min(timeout, curlTimeout);
  if (running < static_cast<size_t>(opt.maxInFlight)) {
    for (const auto& [seq, t] : transfers) {
      if (t->easy != nullptr) continue;
      const double waitMs = std::ceil((t->notBeforeS - nowS) * 1000.0);
      timeout = std::min(timeout, static_cast<long>(std::clamp(waitMs, 0.0, double(kIdlePollMs))));
    }
  }
  return timeout;
}

Result<std::shared_ptr<HttpTileSource>> HttpTileSource::create(HttpSourceOptions options) {
  assert(options.maxInFlight >= 1 && options.maxAttempts >= 1);
  if (Status s = checkHttpUrl(options.baseUrl); !s) return s.error();
  auto impl = std::make_shared<Impl>();
  impl->log = options.log ? options.log : makeNullLogger();
  if (options.clock) impl->clock = options.clock;
  impl->base = options.baseUrl;
  if (impl->base.back() != '/') impl->base += '/';
  if (options.cacheDir) {
    auto cache = DiskTileCache::open(*options.cacheDir, options.cacheBudgetBytes, impl->log);
    if (!cache) return cache.error();
    impl->cache = std::move(*cache);
  }
  impl->opt = std::move(options);
  impl->multi = curl_multi_init();
  assert(impl->multi != nullptr);
  // Idle connections kept for reuse: one per transfer slot, plus a few for redirects.
  curl_multi_setopt(impl->multi, CURLMOPT_MAXCONNECTS, static_cast<long>(impl->opt.maxInFlight + 4));
  curl_multi_setopt(impl->multi, CURLMOPT_PIPELINING, static_cast<long>(CURLPIPE_MULTIPLEX));
  std::unique_ptr<ThreadPool> ownPool;
  TaskRunner* runner = impl->opt.tasks;
  if (!runner) {
    ownPool = std::make_unique<ThreadPool>(1);
    runner = ownPool.get();
  }
  runner->postLongRunning([impl] { impl->runOnce(); });
  return std::shared_ptr<HttpTileSource>(new HttpTileSource(std::move(impl), std::move(ownPool)));
}

HttpTileSource::HttpTileSource(std::shared_ptr<Impl> impl, std::unique_ptr<ThreadPool> ownPool)
    : ownPool_(std::move(ownPool)), impl_(std::move(impl)) {}

HttpTileSource::~HttpTileSource() {
  {
    std::lock_guard lock(impl_->mutex);
    impl_->stopping = true;
  }
  curl_multi_wakeup(impl_->multi);
  impl_->runOnce();  // the task never ran (a runner that is not running): shut down here
  {
    std::unique_lock lock(impl_->mutex);
    impl_->loopDone.wait(lock, [&] { return impl_->loop == Impl::Loop::Done; });
  }
  curl_multi_cleanup(impl_->multi);
  impl_->multi = nullptr;
}

void HttpTileSource::wake() { curl_multi_wakeup(impl_->multi); }

std::string HttpTileSource::describe() const { return impl_->opt.baseUrl; }

std::string HttpTileSource::urlFor(const std::string& relativePath) const {
  return impl_->base + percentEncodePath(relativePath);
}

Result<std::string> HttpTileSource::readText(const std::string& relativePath) {
  auto t = std::make_unique<Transfer>();
  t->isTile = false;
  t->url = urlFor(relativePath);
  // Shared, so that set_value never runs on a promise this frame has already destroyed.
  auto promise = std::make_shared<std::promise<FetchResult>>();
  std::future<FetchResult> future = promise->get_future();
  t->done = [promise](FetchResult&& r) { promise->set_value(std::move(r)); };
  const std::string url = t->url;
  impl_->post(Command{std::move(t), 0});
  FetchResult r = future.get();
  switch (r.outcome) {
    case FetchOutcome::Ok: return std::string(r.bytes.begin(), r.bytes.end());
    case FetchOutcome::Missing: return makeError(ErrorKind::NotFound, r.message);
    case FetchOutcome::Cancelled: return makeError(ErrorKind::Io, "GET " + url + ": " + r.message);
    case FetchOutcome::Failed: break;
  }
  return makeError(ErrorKind::Io, r.message);
}

void HttpTileSource::start(RequestId id, const std::string& relativePath, FetchCallback done) {
  auto t = std::make_unique<Transfer>();
  t->id = id;
  t->url = urlFor(relativePath);
  t->cacheKey = t->url.substr(t->url.find("://") + 3);
  t->done = std::move(done);
  impl_->post(Command{std::move(t), 0});
}

void HttpTileSource::cancel(RequestId id) { impl_->post(Command{nullptr, id}); }

std::size_t HttpTileSource::inFlight() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->live.size();
}

SourceCounters HttpTileSource::counters() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->counters;
}

HttpTransportStats HttpTileSource::transportStats() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->transport;
}

}  // namespace vegstream::streaming
