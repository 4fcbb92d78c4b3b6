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

#include "datasets/http_limits.h"
#include "datasets/http_retry_policy.h"
#include "streaming/disk_tile_cache.h"
#include "streaming/http_transfer.h"
#include "streaming/http_url.h"

namespace vegstream::streaming {
namespace {
using datasets::AttemptEnd;
using datasets::AttemptVerdict;
using datasets::backoffDelayMs;
using datasets::judgeAttempt;
using detail::configureAttempt;
using detail::readAttemptEnd;
using detail::Transfer;

constexpr long kIdlePollMs = 1000;  // upper bound of one curl_multi_poll wait
constexpr int kMaxRedirects = 5;  // per request

struct Command {
  std::unique_ptr<Transfer> start;  // null: cancel `cancelId`
  RequestId cancelId = 0;
};

}  // namespace

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
  std::shared_ptr<const TileCheck> tileCheck;  // null: none set

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
  bool followRedirect(Transfer& t, const AttemptEnd& end);
  Status checkTile(const Transfer& t, std::span<const uint8_t> bytes);
  void retryOrFail(Transfer& t);
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
  if (cached) {
    if (Status s = checkTile(*t, *cached); !s) {  // a copy from an older run, or a bad disk: fetch it again
      log->warn("tile cache: dropped {}: {}", t->cacheKey, s.error().message);
      cache->remove(t->cacheKey);
      cached.reset();
    }
  }
  transfers.emplace(seq, std::move(t));
  if (cached) {
    transfers[seq]->body.bytes = std::move(*cached);
    complete(seq, FetchOutcome::Ok, {});
  }
}

Status HttpTileSource::Impl::checkTile(const Transfer& t, std::span<const uint8_t> bytes) {
  std::shared_ptr<const TileCheck> check;
  {
    std::lock_guard lock(mutex);
    check = tileCheck;
  }
  if (!check) return {};
  return (*check)(t.path, bytes);
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
  const double nowS = clock->nowS();
  if (t.attempts == 0 && t.redirects == 0) t.deadlineS = nowS + static_cast<double>(opt.requestDeadlineMs) / 1000.0;
  configureAttempt(e, t, opt, nowS);
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
  const AttemptEnd end = readAttemptEnd(t, code, opt.maxBodyBytes);
  if (code == CURLE_OK && datasets::isRedirectStatus(end.httpStatus) && followRedirect(t, end)) return;
  stopRunning(t);

  AttemptVerdict verdict = judgeAttempt(end);
  if (verdict == AttemptVerdict::Ok && t.isTile && cache) {
    if (Status s = checkTile(t, t.body.bytes); !s) {
      t.lastProblem = "not the tile it claims to be: " + s.error().message;
      verdict = AttemptVerdict::Retry;  // a proxy's error page may be gone next time; never cached
    } else if (Status put = cache->put(t.cacheKey, t.body.bytes); !put) {
      log->warn("tile cache: {}", put.error().message);
    }
  }
  if (verdict == AttemptVerdict::Ok) {
    complete(t.seq, FetchOutcome::Ok, {});
  } else if (verdict == AttemptVerdict::Missing) {
    complete(t.seq, FetchOutcome::Missing, "GET " + t.requestUrl + ": " + t.lastProblem);
  } else if (verdict == AttemptVerdict::Retry && t.attempts < opt.maxAttempts) {
    retryOrFail(t);
  } else {
    complete(t.seq, FetchOutcome::Failed,
             "GET " + t.requestUrl + ": " + t.lastProblem + " (" + std::to_string(t.attempts) + " attempts)");
  }
}

// A 3xx: true when the transfer goes on at the redirect's target (relaunched at once, not an
// attempt); false when the redirect is refused, with t.lastProblem saying why (then Failed).
bool HttpTileSource::Impl::followRedirect(Transfer& t, const AttemptEnd& end) {
  const std::optional<std::string> target = detail::redirectHop(t, end.httpStatus, opt.allowRedirects, kMaxRedirects);
  if (!target) return false;
  stopRunning(t);
  log->debug("GET {}: HTTP {} to {}", t.requestUrl, end.httpStatus, *target);
  t.url = *target;
  ++t.redirects;
  --t.attempts;  // launch() counts it again
  t.notBeforeS = 0.0;
  return true;
}

// After a retryable attempt: the next one after a back-off, unless that passes the deadline.
void HttpTileSource::Impl::retryOrFail(Transfer& t) {
  const long delay = backoffDelayMs(t.attempts + 1, t.seq, opt.backoffBaseMs, opt.backoffMaxMs);
  const double nowS = clock->nowS();
  if (nowS + static_cast<double>(delay) / 1000.0 >= t.deadlineS) {
    complete(t.seq, FetchOutcome::Failed,
             "GET " + t.requestUrl + ": " + t.lastProblem + " (" + std::to_string(t.attempts) +
                 " attempts; the request's deadline of " + std::to_string(opt.requestDeadlineMs) + " ms passed)");
    return;
  }
  log->debug("GET {}: {}; attempt {} in {} ms", t.requestUrl, t.lastProblem, t.attempts + 1, delay);
  t.notBeforeS = nowS + static_cast<double>(delay) / 1000.0;
  if (t.isTile) {
    std::lock_guard lock(mutex);
    ++counters.retries;
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
  if (outcome == FetchOutcome::Ok) r.bytes = std::move(t->body.bytes);
  if (outcome == FetchOutcome::Missing || outcome == FetchOutcome::Failed) log->debug("{}", r.message);
  if (t->isTile) {
    seqOfTile.erase(t->id);
    std::lock_guard lock(mutex);
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
  // Live until its callback has returned (as LocalTileSource): a caller that sees inFlight()
  // drop knows the result was handed on (tile_source.h).
  if (t->isTile) {
    std::lock_guard lock(mutex);
    live.erase(t->id);
  }
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
  t->url = t->requestUrl = urlFor(relativePath);
  t->path = relativePath;
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
  // As the importer's URL sources (datasets/http_fetch.h): the URL the user named does not
  // deliver, after every retry — a message naming it, exit 2.
  return makeError(ErrorKind::InvalidInput, r.message);
}

void HttpTileSource::start(RequestId id, const std::string& relativePath, FetchCallback done) {
  auto t = std::make_unique<Transfer>();
  t->id = id;
  t->url = t->requestUrl = urlFor(relativePath);
  t->path = relativePath;
  t->cacheKey = t->url.substr(t->url.find("://") + 3);
  t->done = std::move(done);
  impl_->post(Command{std::move(t), 0});
}

void HttpTileSource::cancel(RequestId id) { impl_->post(Command{nullptr, id}); }

std::size_t HttpTileSource::inFlight() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->live.size();
}

void HttpTileSource::setTileCheck(TileCheck check) {
  std::lock_guard lock(impl_->mutex);
  impl_->tileCheck = check ? std::make_shared<const TileCheck>(std::move(check)) : nullptr;
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
