// HttpTileSource's I/O task (http_source_impl.h): one long-running loop over one libcurl multi
// handle that takes the callers' commands, launches transfers within the in-flight limit, ends
// their attempts (redirects, retries after a back-off, the disk cache, the tile check) and calls
// each request back once.
#include <algorithm>
#include <cassert>
#include <cmath>

#include "datasets/http_limits.h"
#include "streaming/http_source_impl.h"

namespace vegstream::streaming {
namespace {
using datasets::AttemptVerdict;
using datasets::backoffDelayMs;
using datasets::judgeAttempt;
using detail::configureAttempt;
using detail::readAttemptEnd;

constexpr long kIdlePollMs = 1000;  // upper bound of one curl_multi_poll wait
constexpr int kMaxRedirects = 5;    // per request

}  // namespace

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
    countOutcome(counters, outcome, r.bytes.size());
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

}  // namespace vegstream::streaming
