// HttpTileSource (http_tile_source.h): one long-running I/O task (http_io_loop.cpp), one libcurl
// multi handle; here its creation and shutdown and the callers' side (start, cancel, readText,
// the counters). The threads and what `mutex` guards: http_source_impl.h.

#include "streaming/http_source_impl.h"

#include <cassert>
#include <future>

#include <curl/curl.h>

#include "streaming/http_url.h"

namespace vegstream::streaming {
using detail::Transfer;
using http_source::Command;

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
