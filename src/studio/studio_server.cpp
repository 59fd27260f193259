// The studio's routes. Handlers run on httplib's thread pool; each turns the library's
// errors into JSON (with line:column) so that no model can take the server down.
#include "graftal/studio/studio_server.hpp"

#include <httplib.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "graftal/core/atomic_file.hpp"
#include "graftal/core/file_format.hpp"
#include "graftal/studio/studio_guard.hpp"
#include "graftal/studio/studio_sessions.hpp"

namespace graftal::studio {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Text from the user's files (a model, an error message quoting it) may be any bytes: bytes
// that are not UTF-8 go out as U+FFFD rather than failing the answer.
std::string jsonText(const json& body) {
    return body.dump(-1, ' ', false, json::error_handler_t::replace);
}

void sendJson(httplib::Response& res, const json& body, int status = 200) {
    res.status = status;
    res.set_content(jsonText(body), "application/json; charset=utf-8");
}

void sendError(httplib::Response& res, int status, const std::string& message,
               const std::vector<Diagnostic>& diagnostics = {}) {
    sendJson(res, {{"error", message}, {"diagnostics", diagnosticsJson(diagnostics)}}, status);
}

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(SourceLocation{path.string(), 0, 0}, "cannot read the file");
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

// The export menu's entries: the registry's rows the studio offers, grouped by kind.
json formatsJson() {
    json formats = json::array();
    for (const ExportFormat* f : studioExportFormats())
        formats.push_back({{"name", f->name},
                           {"extension", f->extension},
                           {"kind", exportKindName(f->kind)},
                           {"description", f->description}});
    return formats;
}

json parseBody(const httplib::Request& req) {
    try {
        json body = json::parse(req.body);
        if (!body.is_object()) throw BadRequest("the body must be a JSON object");
        return body;
    } catch (const json::exception& e) {
        throw BadRequest(std::string("the body is not JSON: ") + e.what());
    }
}

bool isIdentifier(const std::string& s) {
    if (s.empty() || s.size() > 64) return false;
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
    return !std::isdigit(static_cast<unsigned char>(s[0]));
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

// Milliseconds since 1970, as the page's performance.timeOrigin + performance.now().
double epochMilliseconds() {
    return std::chrono::duration<double, std::milli>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
}

// Counts the derivations the page waits for while it lives; thumbnails wait for none.
class LiveRequest {
  public:
    explicit LiveRequest(std::atomic<int>& count) : count_(count) { ++count_; }
    ~LiveRequest() { --count_; }
    LiveRequest(const LiveRequest&) = delete;
    LiveRequest& operator=(const LiveRequest&) = delete;

  private:
    std::atomic<int>& count_;
};

const char* contentTypeFor(const std::string& extension) {
    static const std::map<std::string, const char*> types = {
        {".png", "image/png"},
        {".svg", "image/svg+xml; charset=utf-8"},
        {".pdf", "application/pdf"},
        {".glb", "model/gltf-binary"},
        {".ply", "application/octet-stream"},
        {".zip", "application/zip"},
        {".gif", "image/gif"},
        {".webp", "image/webp"},
        {".mp4", "video/mp4"},
        {".mid", "audio/midi"},
        {".wav", "audio/wav"},
        {".musicxml", "application/vnd.recordare.musicxml+xml"},
        {".ly", "text/x-lilypond; charset=utf-8"}};
    const auto it = types.find(extension);
    return it == types.end() ? "application/octet-stream" : it->second;
}

// One request's bytes in, the answer's bytes out: a connection without a socket.
class MemoryStream final : public httplib::Stream {
  public:
    explicit MemoryStream(std::string_view request) : request_(request) {}
    bool is_readable() const override { return position_ < request_.size(); }
    bool is_writable() const override { return true; }
    ssize_t read(char* ptr, size_t size) override {
        const size_t n = std::min(size, request_.size() - position_);
        std::memcpy(ptr, request_.data() + position_, n);
        position_ += n;
        return static_cast<ssize_t>(n);
    }
    ssize_t write(const char* ptr, size_t size) override {
        answer_.append(ptr, size);
        return static_cast<ssize_t>(size);
    }
    void get_remote_ip_and_port(std::string& ip, int& port) const override {
        ip = "127.0.0.1";
        port = 0;
    }
    void get_local_ip_and_port(std::string& ip, int& port) const override {
        ip = "127.0.0.1";
        port = 0;
    }
    socket_t socket() const override { return INVALID_SOCKET; }
    std::string& answer() { return answer_; }

  private:
    std::string_view request_;
    size_t position_ = 0;
    std::string answer_;
};

// httplib's server with its request processing reachable without a socket, so that the
// routes can be driven directly (StudioServer::answer).
class HttpServer final : public httplib::Server {
  public:
    std::string answer(std::string_view request) {
        MemoryStream stream(request);
        bool closed = false;
        process_request(stream, true, closed, nullptr);
        return std::move(stream.answer());
    }
};

}  // namespace

struct StudioServer::Impl {
    StudioOptions options;
    StudioRoot root;
    fs::path scratch;
    HttpServer server;
    std::thread thread;
    StudioSessions sessions;
    std::atomic<bool> stopping{false};
    std::atomic<int> liveRequests{0};  // derivations for the live view under way
    int port = 0;
    std::mutex thumbnailMutex;  // one thumbnail at a time: the live view comes first
    std::map<std::string, std::pair<std::int64_t, std::string>> thumbnails;

    DerivationGate gate;

    explicit Impl(StudioOptions o)
        : options(std::move(o)),
          root(options.root),
          gate(std::max(1, options.maxDerivations), options.memoryBudget) {
        if (options.requireToken && options.token.empty()) options.token = randomToken();
        if (!options.requireToken) options.token.clear();
        scratch =
            fs::temp_directory_path() / ("graftal-studio-" + std::to_string(::getpid()) + "-" +
                                         std::to_string(reinterpret_cast<std::uintptr_t>(this)));
        fs::create_directories(scratch);
        routes();
    }

    ~Impl() {
        std::error_code ec;
        fs::remove_all(scratch, ec);
    }

    // Runs a handler and answers every failure as JSON.
    template <typename F>
    httplib::Server::Handler guarded(F handler) {
        return [handler](const httplib::Request& req, httplib::Response& res) {
            try {
                handler(req, res);
            } catch (const PathRefused& e) {
                sendError(res, 403, e.messages());
            } catch (const Cancelled&) {
                sendJson(res,
                         {{"error", "cancelled: a newer request replaced it"}, {"cancelled", true}},
                         409);
            } catch (const Error& e) {
                sendError(res, 422, e.messages(), e.diagnostics());
            } catch (const BadRequest& e) {
                sendError(res, 400, e.what());
            } catch (const Busy& e) {
                sendError(res, 503, e.what());
            } catch (const std::bad_alloc&) {
                sendError(res, 507, "out of memory: lower the steps");
            } catch (const std::exception& e) {
                sendError(res, 500, e.what());
            }
        };
    }

    ModelInput modelInput(const json& body) const {
        ModelInput input;
        if (!body.contains("text") || !body["text"].is_string())
            throw BadRequest("the body needs the model's \"text\"");
        input.text = body["text"].get<std::string>();
        if (body.contains("path") && body["path"].is_string() &&
            !body["path"].get<std::string>().empty())
            input.file = root.resolve(body["path"].get<std::string>(), false);
        else
            input.file = root.folder() / "untitled.l";
        // Its view file, when the root lets the studio read it.
        input.viewFile = viewFileOf(input.file);
        if (!input.viewFile.empty()) input.viewText = readFile(input.viewFile);
        // Never narrowed: a number past an int is refused here, one past the studio's
        // limit by the derivation (with the limit in its message).
        if (body.contains("steps") && !body["steps"].is_null())
            input.steps =
                static_cast<int>(integerField(body, "steps", 0, std::numeric_limits<int>::max()));
        if (body.contains("defines") && body["defines"].is_object()) {
            if (body["defines"].size() > 200) throw BadRequest("too many defines");
            for (const auto& [name, value] : body["defines"].items()) {
                if (!isIdentifier(name)) throw BadRequest("'" + name + "' is not a define's name");
                if (value.is_number()) {
                    numberField(value, name, -1e300, 1e300);  // finite, as the text's would be
                    input.defines[name] = value.dump();
                } else if (value.is_string() && value.get<std::string>().size() < 200)
                    input.defines[name] = value.get<std::string>();
                else
                    throw BadRequest("the define " + name + " needs a number");
            }
        }
        return input;
    }

    // The view file of a model file inside the root (empty when none or refused).
    fs::path viewFileOf(const fs::path& file) const {
        const fs::path view = viewFileBeside(file);
        if (view.empty()) return {};
        try {
            return root.resolve(view.lexically_relative(root.folder()).generic_string(), true);
        } catch (const PathRefused&) {
            return {};
        }
    }

    static std::string sessionOf(const json& body) {
        if (body.contains("session") && body["session"].is_string())
            return body["session"].get<std::string>().substr(0, 100);
        return "default";
    }

    void serveAsset(const std::string& url, const std::string& file, const char* type) {
        server.Get(url,
                   guarded([this, file, type](const httplib::Request&, httplib::Response& res) {
                       const fs::path path = options.assets / file;
                       if (options.assets.empty() || !fs::exists(path)) {
                           sendError(res, 404, "the studio's page was not built (" + file + ")");
                           return;
                       }
                       res.set_content(readFile(path), type);
                       res.set_header("Cache-Control", "no-cache");
                       // The page's own requests (and its thumbnails' <img>) carry the token
                       // as a cookie that no other site's page is sent.
                       if (!options.token.empty() && file == "index.html")
                           res.set_header("Set-Cookie", cookieName() + "=" + options.token +
                                                            "; Path=/; HttpOnly; SameSite=Strict");
                   }));
    }

    // A slot and a share of the memory budget for one derivation, and the limits it runs
    // under (its memory limit is its share).
    DerivationGate::Pass enterGate(const CancellationToken& token, StudioLimits& limits) {
        DerivationGate::Pass pass =
            gate.enter(limits.memoryLimit, limits.memoryLimit / 4, token,
                       std::chrono::milliseconds(options.busyWaitMilliseconds));
        limits.memoryLimit = pass.bytes();
        return pass;
    }

    std::string cookieName() const { return "graftal-studio-" + std::to_string(port); }

    // The request carries this run's token (or none is required).
    bool authorised(const httplib::Request& req) const {
        if (options.token.empty()) return true;
        return sameSecret(req.get_param_value("token"), options.token) ||
               sameSecret(req.get_header_value("X-Graftal-Token"), options.token) ||
               sameSecret(cookieValue(req.get_header_value("Cookie"), cookieName()), options.token);
    }

    // Refuses what a studio should not answer before its body is read: another host (DNS
    // rebinding), another site's page (Origin), a request without the token, and a chunked
    // body (its length is not known before reading it; the page always sends a length).
    bool refused(const httplib::Request& req, httplib::Response& res) const {
        const std::string host = req.get_header_value("Host");
        const std::string p = ":" + std::to_string(port);
        if (host != "127.0.0.1" + p && host != "localhost" + p) {
            sendError(res, 403, "the studio answers only 127.0.0.1 and localhost");
            return true;
        }
        if (req.has_header("Origin") && !isOwnOrigin(req.get_header_value("Origin"), port)) {
            sendError(res, 403,
                      "the studio answers only its own page, not one from " +
                          req.get_header_value("Origin").substr(0, 100));
            return true;
        }
        const bool asset = req.path == "/studio.js" || req.path == "/studio.css";
        if (!asset && !authorised(req)) {
            sendError(res, 403,
                      "this studio needs its token: open the address `graftal studio` printed "
                      "(http://127.0.0.1" +
                          p + "/?token=...)");
            return true;
        }
        std::string encoding = req.get_header_value("Transfer-Encoding");
        for (char& c : encoding) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (encoding.find("chunked") != std::string::npos) {
            sendError(res, 411,
                      "the studio reads a body only with its Content-Length (at most " +
                          std::to_string(options.limits.bodyBytes) + " bytes), not chunked");
            res.set_header("Connection", "close");
            return true;
        }
        return false;
    }

    void routes() {
        server.set_payload_max_length(options.limits.bodyBytes);
        // httplib writes an answer's headers and its body apart. With Nagle's algorithm on,
        // the body's last piece waits for the headers' ACK, which the browser delays by up
        // to 40 ms (it has nothing to send back): a third of a keystroke's time budget.
        // Debian builds httplib as a library, so CPPHTTPLIB_TCP_NODELAY defined here would
        // not reach the server's constructor: the setting is made at run time.
        server.set_tcp_nodelay(true);
        // Only this machine's own pages: a page of another site that points a name at
        // 127.0.0.1 (DNS rebinding) names its own host.
        server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
            return refused(req, res) ? httplib::Server::HandlerResponse::Handled
                                     : httplib::Server::HandlerResponse::Unhandled;
        });

        serveAsset("/", "index.html", "text/html; charset=utf-8");
        // httplib compresses text/* and a bare application/javascript with brotli at its
        // highest quality on every request (seconds for the megabyte bundle); with a
        // charset the type is left alone.
        serveAsset("/studio.js", "studio.js", "application/javascript; charset=utf-8");
        serveAsset("/studio.css", "studio.css", "text/css; charset=utf-8");

        server.Get("/api/info", guarded([this](const httplib::Request&, httplib::Response& res) {
                       sendJson(res, {{"root", root.folder().string()},
                                      {"onlyFile", root.onlyFile()},
                                      {"formats", formatsJson()},
                                      {"limits",
                                       {{"bodyBytes", options.limits.bodyBytes},
                                        {"segmentBudget", options.limits.segmentBudget},
                                        {"meshSegmentBudget", options.limits.meshSegmentBudget},
                                        {"maxSteps", options.limits.maxSteps}}}});
                   }));

        server.Get(
            "/api/files", guarded([this](const httplib::Request&, httplib::Response& res) {
                json files = json::array();
                for (const ListedFile& f : root.list())
                    files.push_back({{"path", f.path}, {"size", f.size}, {"mtime", f.mtime}});
                sendJson(res, {{"files", files}});
            }));

        server.Get("/api/file",
                   guarded([this](const httplib::Request& req, httplib::Response& res) {
                       const fs::path path = root.resolve(req.get_param_value("path"), true);
                       sendJson(res, {{"path", req.get_param_value("path")},
                                      {"text", readFile(path)},
                                      {"mtime", modificationTime(path)}});
                   }));

        server.Put(
            "/api/file", guarded([this](const httplib::Request& req, httplib::Response& res) {
                const fs::path path = root.resolve(req.get_param_value("path"), false);
                writeStreamAtomically(
                    path, [&](std::ostream& out) { out.write(req.body.data(), req.body.size()); },
                    "model file");
                sendJson(res, {{"path", req.get_param_value("path")},
                               {"mtime", modificationTime(path)}});
            }));

        // Long poll: answers when the file's time differs from `since`, or after a while.
        server.Get(
            "/api/watch", guarded([this](const httplib::Request& req, httplib::Response& res) {
                const fs::path path = root.resolve(req.get_param_value("path"), true);
                std::int64_t since = 0;
                if (req.has_param("since")) {
                    const std::string text = req.get_param_value("since");
                    const auto [end, ec] =
                        std::from_chars(text.data(), text.data() + text.size(), since);
                    if (ec != std::errc() || end != text.data() + text.size())
                        throw BadRequest(
                            "\"since\" must be a file time in microseconds (a "
                            "whole number), got '" +
                            text.substr(0, 40) + "'");
                }
                const auto until = std::chrono::steady_clock::now() +
                                   std::chrono::milliseconds(options.watchMilliseconds);
                std::int64_t now = modificationTime(path);
                while (now == since && !stopping && std::chrono::steady_clock::now() < until) {
                    std::this_thread::sleep_for(std::chrono::milliseconds(100));
                    now = modificationTime(path);
                }
                sendJson(res, {{"mtime", now}, {"changed", now != since}});
            }));

        server.Post("/api/parse",
                    guarded([this](const httplib::Request& req, httplib::Response& res) {
                        sendJson(res, parseReport(modelInput(parseBody(req))));
                    }));

        // Metadata and geometry in one answer: a 4-byte JSON length, the JSON, padding to
        // a multiple of 4, then the line buffer (encodeLines) or a summarised PNG. A
        // request whose picture key is the session's last one reuses that picture; when the
        // page says it shows it already (`have`: its tag) the answer carries no geometry.
        server.Post(
            "/api/derive", guarded([this](const httplib::Request& req, httplib::Response& res) {
                const auto received = std::chrono::steady_clock::now();
                const double receivedAt = epochMilliseconds();
                const json body = parseBody(req);
                const ModelInput input = modelInput(body);
                const std::string session = sessionOf(body);
                const std::string key = pictureKey(input);
                const std::string tag = pictureTag(key);
                const CancellationToken token = sessions.begin(session);
                // The parse report comes with the picture (or the errors): one
                // request a keystroke, one parse of the text.
                ParseResult parsed = parseInput(input);
                const json report = parseReport(input, parsed);
                if (!parsed.ok()) {
                    sendJson(res,
                             {{"error", Error(parsed.errors()).messages()},
                              {"diagnostics", report["diagnostics"]},
                              {"report", report}},
                             422);
                    return;
                }
                std::shared_ptr<const StudioPicture> picture = sessions.kept(session, key);
                const bool reused = picture != nullptr;
                const bool unchanged = reused && body.value("have", "") == tag;
                if (!picture) {
                    LiveRequest live(liveRequests);
                    StudioLimits limits = options.limits;
                    const DerivationGate::Pass pass = enterGate(token, limits);
                    try {
                        picture = std::make_shared<StudioPicture>(
                            derivePicture(input, std::move(parsed.model), limits, token, scratch));
                    } catch (const Cancelled&) {
                        throw;
                    } catch (const Error& e) {  // the turtle's, the limits': with the report
                        sendJson(res,
                                 {{"error", e.messages()},
                                  {"diagnostics", diagnosticsJson(e.diagnostics())},
                                  {"report", report}},
                                 422);
                        return;
                    }
                    sessions.keep(session, key, picture);
                }
                const bool summarised = !picture->summaryPng.empty();
                json stats = picture->stats;
                if (reused) stats["encodeMs"] = 0;
                stats["reused"] = reused;
                stats["serverMs"] = millisecondsSince(received);
                // The page's clock and this one are the machine's: it splits the
                // time before, in and after the server with these.
                stats["receivedAt"] = receivedAt;
                stats["answeredAt"] = epochMilliseconds();
                json meta = {
                    {"stats", stats},
                    {"report", report},
                    {"steps", picture->steps},
                    {"tag", tag},
                    {"unchanged", unchanged},
                    {"string", unchanged ? std::string() : picture->stringHead},
                    {"notes", picture->notes},
                    {"geometry", unchanged    ? "none"
                                 : summarised ? "png"
                                              : "lines"},
                    {"meshAvailable",
                     !summarised && picture->segments <= options.limits.meshSegmentBudget}};
                std::string out(4, '\0');
                const std::string metaText = jsonText(meta);
                const std::uint32_t length = static_cast<std::uint32_t>(metaText.size());
                std::memcpy(out.data(), &length, 4);
                out += metaText;
                out.append((4 - out.size() % 4) % 4, ' ');
                if (!unchanged) out += summarised ? picture->summaryPng : picture->lines;
                res.set_content(std::move(out), "application/octet-stream");
            }));

        // The 3D view's mesh, from the picture the last derive made (or derived again).
        server.Post("/api/mesh",
                    guarded([this](const httplib::Request& req, httplib::Response& res) {
                        const json body = parseBody(req);
                        const ModelInput input = modelInput(body);
                        const std::string session = sessionOf(body);
                        std::shared_ptr<const StudioPicture> picture =
                            sessions.kept(session, pictureKey(input));
                        if (!picture) {
                            const CancellationToken token = sessions.begin(session);
                            LiveRequest live(liveRequests);
                            StudioLimits limits = options.limits;
                            const DerivationGate::Pass pass = enterGate(token, limits);
                            picture = std::make_shared<StudioPicture>(
                                derivePicture(input, limits, token, scratch));
                        }
                        if (!picture->summaryPng.empty() ||
                            picture->segments > options.limits.meshSegmentBudget) {
                            sendError(res, 413,
                                      "over the mesh budget of " +
                                          std::to_string(options.limits.meshSegmentBudget) +
                                          " segments: the 3D view draws lines");
                            return;
                        }
                        res.set_content(meshGlb(*picture, scratch), "model/gltf-binary");
                    }));

        server.Post(
            "/api/export", guarded([this](const httplib::Request& req, httplib::Response& res) {
                const json body = parseBody(req);
                const ModelInput input = modelInput(body);
                const std::string format = body.value("format", "");
                const auto& formats = studioExportFormats();
                if (std::none_of(formats.begin(), formats.end(),
                                 [&](const ExportFormat* f) { return f->name == format; }))
                    throw BadRequest("unknown export format '" + format.substr(0, 20) + "'");
                const CancellationToken token = sessions.begin(sessionOf(body) + "/export");
                StudioLimits limits = options.limits;
                const DerivationGate::Pass pass = enterGate(token, limits);
                ExportedFile file = exportFile(input, format, limits, token, scratch);
                res.set_header("Content-Disposition",
                               "attachment; filename=\"" + file.fileName + "\"");
                res.set_content(std::move(file.bytes),
                                contentTypeFor(fs::path(file.fileName).extension().string()));
            }));

        server.Get("/api/thumbnail",
                   guarded([this](const httplib::Request& req, httplib::Response& res) {
                       const std::string rel = req.get_param_value("path");
                       const fs::path path = root.resolve(rel, true);
                       // Redrawn when the model or its view file changes.
                       const fs::path view = viewFileOf(path);
                       const std::int64_t mtime =
                           modificationTime(path) + (view.empty() ? 1 : modificationTime(view));
                       std::lock_guard lock(thumbnailMutex);
                       // The live view first: a thumbnail waits (a while) for its derivations.
                       for (int i = 0; i < 200 && liveRequests > 0 && !stopping; ++i)
                           std::this_thread::sleep_for(std::chrono::milliseconds(50));
                       auto it = thumbnails.find(rel);
                       if (it == thumbnails.end() || it->second.first != mtime) {
                           StudioLimits limits = options.limits;
                           limits.memoryLimit =
                               std::min<std::size_t>(limits.memoryLimit, std::size_t(256) << 20);
                           limits.deriveSeconds = 20;
                           const DerivationGate::Pass pass = enterGate(CancellationToken{}, limits);
                           thumbnails[rel] = {
                               mtime, thumbnailPng(path, viewFileOf(path), 160, limits, scratch)};
                           it = thumbnails.find(rel);
                       }
                       res.set_header("Cache-Control", "no-cache");
                       res.set_content(it->second.second, "image/png");
                   }));
    }
};

StudioServer::StudioServer(StudioOptions options)
    : impl_(std::make_unique<Impl>(std::move(options))) {}

StudioServer::~StudioServer() {
    stop();
}

int StudioServer::start(int port) {
    Impl& s = *impl_;
    if (port == 0) {
        s.port = s.server.bind_to_any_port("127.0.0.1");
        if (s.port <= 0)
            throw Error(SourceLocation{"studio", 0, 0}, "cannot bind a port on 127.0.0.1");
    } else {
        if (!s.server.bind_to_port("127.0.0.1", port))
            throw Error(SourceLocation{"studio", 0, 0},
                        "cannot bind 127.0.0.1:" + std::to_string(port) + " (in use?)");
        s.port = port;
    }
    s.thread = std::thread([&s] { s.server.listen_after_bind(); });
    return s.port;
}

void StudioServer::wait() {
    if (impl_->thread.joinable()) impl_->thread.join();
}

std::string StudioServer::answer(std::string_view request) {
    return impl_->server.answer(request);
}

const std::string& StudioServer::token() const {
    return impl_->options.token;
}

void StudioServer::stop() {
    if (!impl_) return;
    impl_->stopping = true;
    impl_->server.stop();
    if (impl_->thread.joinable()) impl_->thread.join();
}

}  // namespace graftal::studio
