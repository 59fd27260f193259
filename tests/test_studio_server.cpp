// graftal studio's server, through its HTTP API as the page uses it: a server on a free
// port of 127.0.0.1 in this process, a scratch folder as its root, httplib's client.
#include <gtest/gtest.h>
#include <httplib.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "graftal/lang/model.hpp"
#include "graftal/rewrite/derivation.hpp"
#include "graftal/studio/studio_server.hpp"
#include "graftal/turtle/turtle.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const char* kHilbert = R"(/* Hilbert curve */
#define ANGLE 90
#define STEPS 3
Lsystem: 1
derivation length: STEPS
angle factor: 360 / ANGLE
Axiom: X
X --> -YF+XFX+FY-
Y --> +XF-YFY-FX+
endlsystem
)";

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeText(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
}

class StudioServerTest : public ::testing::Test {
  protected:
    void SetUp() override {
        base = fs::temp_directory_path() /
               ("graftal-studio-test-" + std::to_string(::getpid()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(base);
        root = base / "models";
        fs::create_directories(root / "sub");
        fs::create_directories(base / "assets");
        writeText(root / "hilbert.l", kHilbert);
        writeText(root / "sub" / "nested.l", kHilbert);
        writeText(base / "secret.l", "outside the root\n");
        writeText(base / "assets" / "index.html", "<!doctype html><title>studio</title>");
        writeText(base / "assets" / "studio.js", std::string(200'000, ';'));
        fs::create_symlink(base / "secret.l", root / "link-out.l");
        fs::create_symlink(base, root / "dir-out");

        graftal::studio::StudioOptions options;
        options.root = root;
        options.assets = base / "assets";
        options.limits.bodyBytes = 64 * 1024;
        options.limits.maxSteps = 2000;
        options.watchMilliseconds = 3000;
        server = std::make_unique<graftal::studio::StudioServer>(options);
        port = server->start(0);
        client = std::make_unique<httplib::Client>("127.0.0.1", port);
        client->set_read_timeout(60, 0);
        client->set_default_headers({{"X-Graftal-Token", server->token()}});
    }
    void TearDown() override {
        client.reset();
        server.reset();
        fs::remove_all(base);
    }

    httplib::Result post(const std::string& path, const json& body) {
        return client->Post(path.c_str(), body.dump(), "application/json");
    }
    json model(const std::string& text, const std::string& path = "hilbert.l") {
        return {{"text", text}, {"path", path}, {"session", "s1"}};
    }
    // The derive answer's JSON part and its geometry bytes.
    static std::pair<json, std::string> splitDerive(const std::string& body) {
        std::uint32_t length = 0;
        std::memcpy(&length, body.data(), 4);
        json meta = json::parse(body.substr(4, length));
        std::size_t start = 4 + length;
        start += (4 - start % 4) % 4;
        return {meta, body.substr(start)};
    }

    fs::path base, root;
    std::unique_ptr<graftal::studio::StudioServer> server;
    std::unique_ptr<httplib::Client> client;
    int port = 0;
};

TEST_F(StudioServerTest, ServesThePageAndInfo) {
    auto page = client->Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 200);
    EXPECT_NE(page->body.find("<title>studio</title>"), std::string::npos);
    // The bundle goes out as it is: compressing it on every request took seconds.
    auto script = client->Get("/studio.js", {{"Accept-Encoding", "gzip, deflate, br"}});
    ASSERT_TRUE(script);
    EXPECT_EQ(script->status, 200);
    EXPECT_FALSE(script->has_header("Content-Encoding"));
    EXPECT_EQ(script->body.size(), 200'000u);
    EXPECT_EQ(script->get_header_value("Content-Type").rfind("application/javascript", 0), 0u);
    auto info = client->Get("/api/info");
    ASSERT_TRUE(info);
    EXPECT_EQ(json::parse(info->body)["root"], fs::canonical(root).string());
}

TEST_F(StudioServerTest, ListsModelFilesInsideTheRootOnly) {
    auto res = client->Get("/api/files");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200);
    std::vector<std::string> paths;
    const json listing = json::parse(res->body);
    for (const auto& f : listing["files"]) paths.push_back(f["path"]);
    // The link out of the root and the linked folder are not listed.
    EXPECT_EQ(paths, (std::vector<std::string>{"hilbert.l", "sub/nested.l"}));
}

TEST_F(StudioServerTest, ReadsAndWritesFilesAtomically) {
    auto read = client->Get("/api/file?path=sub/nested.l");
    ASSERT_TRUE(read);
    ASSERT_EQ(read->status, 200);
    EXPECT_EQ(json::parse(read->body)["text"], kHilbert);

    std::string changed = std::string(kHilbert) + "/* edited */\n";
    auto write = client->Put("/api/file?path=sub/nested.l", changed, "text/plain");
    ASSERT_TRUE(write);
    ASSERT_EQ(write->status, 200);
    EXPECT_EQ(readText(root / "sub" / "nested.l"), changed);
    // No temporary file is left beside it.
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(root / "sub")) ++entries;
    EXPECT_EQ(entries, 1);
    auto created = client->Put("/api/file?path=new.l", "Axiom: F\n", "text/plain");
    ASSERT_TRUE(created);
    EXPECT_EQ(created->status, 200);
    EXPECT_EQ(readText(root / "new.l"), "Axiom: F\n");
}

TEST_F(StudioServerTest, RefusesPathsOutsideTheRoot) {
    for (const std::string bad :
         {"../secret.l", "sub/../../secret.l", "/etc/passwd", "%2Fetc%2Fhostname.l", "link-out.l",
          "dir-out/secret.l", "hilbert.txt", ""}) {
        auto read = client->Get(("/api/file?path=" + bad).c_str());
        ASSERT_TRUE(read) << bad;
        EXPECT_EQ(read->status, 403) << bad << ": " << read->body;
        auto write = client->Put(("/api/file?path=" + bad).c_str(), "x", "text/plain");
        ASSERT_TRUE(write) << bad;
        EXPECT_EQ(write->status, 403) << bad;
        auto thumb = client->Get(("/api/thumbnail?path=" + bad).c_str());
        ASSERT_TRUE(thumb) << bad;
        EXPECT_EQ(thumb->status, 403) << bad;
    }
    EXPECT_EQ(readText(base / "secret.l"), "outside the root\n");
    auto derive = post("/api/derive", model(kHilbert, "../secret.l"));
    ASSERT_TRUE(derive);
    EXPECT_EQ(derive->status, 403);
}

TEST_F(StudioServerTest, RefusesOversizedBodiesAndOtherHosts) {
    auto big = post("/api/parse", {{"text", std::string(100 * 1024, 'F')}});
    ASSERT_TRUE(big);
    EXPECT_EQ(big->status, 413);
    auto bigWrite =
        client->Put("/api/file?path=hilbert.l", std::string(100 * 1024, 'F'), "text/plain");
    ASSERT_TRUE(bigWrite);
    EXPECT_EQ(bigWrite->status, 413);
    EXPECT_EQ(readText(root / "hilbert.l"), kHilbert);

    httplib::Headers rebound{{"Host", "attacker.example:" + std::to_string(port)}};
    auto other = client->Get("/api/files", rebound);
    ASSERT_TRUE(other);
    EXPECT_EQ(other->status, 403);
}

TEST_F(StudioServerTest, ParseReportsDiagnosticsWithLineAndColumnAndDefines) {
    auto ok = post("/api/parse", model(kHilbert));
    ASSERT_TRUE(ok);
    json report = json::parse(ok->body);
    EXPECT_TRUE(report["ok"]);
    EXPECT_EQ(report["derivationLength"], 3);
    ASSERT_EQ(report["defines"].size(), 2u);
    EXPECT_EQ(report["defines"][0]["name"], "ANGLE");
    EXPECT_EQ(report["defines"][0]["value"], 90);
    EXPECT_EQ(report["defines"][0]["line"], 2);

    std::string broken = kHilbert;
    broken.replace(broken.find("FY-\nY"), 3, "FY-)");
    auto bad = post("/api/parse", model(broken));
    ASSERT_TRUE(bad);
    json badReport = json::parse(bad->body);
    EXPECT_FALSE(badReport["ok"]);
    ASSERT_FALSE(badReport["diagnostics"].empty());
    EXPECT_EQ(badReport["diagnostics"][0]["severity"], "error");
    EXPECT_EQ(badReport["diagnostics"][0]["line"], 8);
    EXPECT_GT(badReport["diagnostics"][0]["column"].get<int>(), 0);

    auto notJson = client->Post("/api/parse", "{not json", "application/json");
    ASSERT_TRUE(notJson);
    EXPECT_EQ(notJson->status, 400);
}

TEST_F(StudioServerTest, DeriveSendsStatsAndSegmentsAsBinary) {
    json body = model(kHilbert);
    body["steps"] = 2;
    auto res = post("/api/derive", body);
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200);
    auto [meta, geometry] = splitDerive(res->body);
    EXPECT_EQ(meta["steps"], 2);
    EXPECT_EQ(meta["geometry"], "lines");
    // Hilbert curve at step 2: 4^2 - 1 segments.
    EXPECT_EQ(meta["stats"]["segments"], 15);
    EXPECT_EQ(meta["string"].get<std::string>().substr(0, 10), "-+XF-YFY-F");
    std::uint32_t header[6];
    std::memcpy(header, geometry.data(), sizeof header);
    EXPECT_EQ(header[0], 0x334C4647u);
    EXPECT_EQ(header[1], 15u);
    // The curve is one polyline: 16 points and one run of 15 links.
    EXPECT_EQ(header[4], 16u);
    EXPECT_EQ(header[5], 1u);
    float bounds[6];
    std::memcpy(bounds, geometry.data() + 24, sizeof bounds);
    EXPECT_NEAR(bounds[0], 0, 1e-6);
    EXPECT_FLOAT_EQ(bounds[3], 3);  // the step-2 curve spans 3 x 3 units
    std::uint32_t paletteCount = 0;
    std::memcpy(&paletteCount, geometry.data() + 60, 4);
    ASSERT_GT(paletteCount, 0u);
    // Header, palette, the points (x y, 16 bits each), then the run: its link count, width
    // and colour.
    const std::size_t pointsAt = 64 + 4 * paletteCount;
    EXPECT_EQ(geometry.size(), pointsAt + 16 * 4 + 8);
    // The curve runs from (0, 0) up to (0, 1): a third of the box's height.
    std::uint16_t first[4];
    std::memcpy(first, geometry.data() + pointsAt, sizeof first);
    EXPECT_EQ(first[0], 0);
    EXPECT_EQ(first[1], 0);
    EXPECT_EQ(first[2], 0);
    EXPECT_EQ(first[3], 65535 / 3);
    std::uint32_t links = 0;
    std::memcpy(&links, geometry.data() + pointsAt + 16 * 4, 4);
    EXPECT_EQ(links, 15u);

    // A branch is a jump: F[+F]F draws three segments from four points... and a jump back.
    json branched = model(
        "Lsystem: 1\nderivation length: 1\nangle factor: 4\naxiom: A\n"
        "A --> F[+F]F\nendlsystem\n");
    auto [branchMeta, branch] = splitDerive(post("/api/derive", branched)->body);
    std::uint32_t branchHeader[6];
    std::memcpy(branchHeader, branch.data(), sizeof branchHeader);
    EXPECT_EQ(branchHeader[1], 3u);  // segments
    EXPECT_EQ(branchHeader[4], 5u);  // (0,0) (0,1) (-1,1); then (0,1) again, (0,2)
    EXPECT_EQ(branchHeader[5], 3u);  // two links, a jump, one link

    body["defines"] = {{"STEPS", 1}};
    body.erase("steps");
    auto overridden = post("/api/derive", body);
    ASSERT_TRUE(overridden);
    EXPECT_EQ(splitDerive(overridden->body).first["stats"]["segments"], 3);
}

TEST_F(StudioServerTest, AnEditInACommentReusesThePicture) {
    auto first = post("/api/derive", model(kHilbert));
    ASSERT_EQ(first->status, 200);
    auto [meta, geometry] = splitDerive(first->body);
    EXPECT_FALSE(meta["stats"]["reused"]);
    EXPECT_FALSE(geometry.empty());
    const std::string tag = meta["tag"];

    // A comment and spacing edited: the same picture, and the page that has it gets none.
    std::string commented = kHilbert;
    commented.replace(commented.find("Hilbert curve"), 13, "Hilbert's curve, edited");
    commented.replace(commented.find("Axiom: X"), 8, "Axiom:    X   ");
    json body = model(commented);
    body["have"] = tag;
    auto again = splitDerive(post("/api/derive", body)->body);
    EXPECT_EQ(again.first["tag"], tag);
    EXPECT_TRUE(again.first["unchanged"]);
    EXPECT_EQ(again.first["geometry"], "none");
    EXPECT_TRUE(again.second.empty());
    // Without `have` the kept picture is sent again.
    body.erase("have");
    auto resent = splitDerive(post("/api/derive", body)->body);
    EXPECT_TRUE(resent.first["stats"]["reused"]);
    EXPECT_EQ(resent.second, geometry);

    // A production edited: a new picture.
    std::string edited = kHilbert;
    edited.replace(edited.find("X --> -YF"), 9, "X --> +YF");
    body = model(edited);
    body["have"] = tag;
    auto changed = splitDerive(post("/api/derive", body)->body);
    EXPECT_NE(changed.first["tag"], tag);
    EXPECT_FALSE(changed.first["unchanged"]);
    EXPECT_FALSE(changed.first["stats"]["reused"]);
    EXPECT_NE(changed.second, geometry);
}

TEST_F(StudioServerTest, TheViewFileBesideTheModelAppliesToTheEditedText) {
    // hilbert.v turns by 45 degrees where the text says 90: the picture follows the view
    // file, as `graftal render hilbert.l hilbert.v` draws it.
    writeText(root / "hilbert.v", "angle increment: 45\n");
    auto report = json::parse(post("/api/parse", model(kHilbert))->body);
    EXPECT_EQ(report["viewFile"], "hilbert.v");
    auto [meta, geometry] = splitDerive(post("/api/derive", model(kHilbert))->body);
    graftal::ParseOptions options;
    options.viewFile = (root / "hilbert.v").string();
    const graftal::Model expected = graftal::loadModel(root / "hilbert.l", options).orThrow();
    const graftal::Bounds b = graftal::interpret(expected, graftal::derive(expected, -1)).bounds();
    EXPECT_NEAR(meta["stats"]["bbox"]["max"][0].get<double>(), b.max.x, 1e-9);
    EXPECT_NEAR(meta["stats"]["bbox"]["min"][1].get<double>(), b.min.y, 1e-9);
    // The same text in a folder without a view file: the text's 90 degrees, a 7 x 7 box.
    auto plain = splitDerive(post("/api/derive", model(kHilbert, "sub/nested.l"))->body).first;
    EXPECT_FLOAT_EQ(plain["stats"]["bbox"]["max"][0].get<float>(), 7);
    EXPECT_NE(plain["stats"]["bbox"], meta["stats"]["bbox"]);

    // A model folder (one .l, one .v) uses its view file whatever its name; a problem in it
    // is a warning naming the view file (cpfg forgives its view files).
    fs::create_directories(root / "plant");
    writeText(root / "plant" / "plant.l", kHilbert);
    writeText(root / "plant" / "view.v", "angle increment: x\n");
    auto bad = json::parse(post("/api/parse", model(kHilbert, "plant/plant.l"))->body);
    EXPECT_EQ(bad["viewFile"], "view.v");
    EXPECT_TRUE(bad["ok"]);
    ASSERT_FALSE(bad["diagnostics"].empty());
    EXPECT_EQ(bad["diagnostics"][0]["file"], "view.v");
    EXPECT_EQ(bad["diagnostics"][0]["line"], 1);
    EXPECT_EQ(post("/api/derive", model(kHilbert, "plant/plant.l"))->status, 200);
}

TEST_F(StudioServerTest, BadModelsAnswerErrorsAndTheServerGoesOn) {
    auto bad = post("/api/derive", model("Axiom: F\nF --> F[\nderivation length: 2\n"));
    ASSERT_TRUE(bad);
    EXPECT_EQ(bad->status, 422);
    EXPECT_TRUE(json::parse(bad->body).contains("error"));
    json tooLong = model(kHilbert);
    tooLong["steps"] = 5000;
    auto refused = post("/api/derive", tooLong);
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 422);
    EXPECT_NE(refused->body.find("limit"), std::string::npos);
    auto after = post("/api/derive", model(kHilbert));
    ASSERT_TRUE(after);
    EXPECT_EQ(after->status, 200);
}

TEST_F(StudioServerTest, MeshIsGlb) {
    ASSERT_EQ(post("/api/derive", model(kHilbert))->status, 200);
    auto mesh = post("/api/mesh", model(kHilbert));
    ASSERT_TRUE(mesh);
    ASSERT_EQ(mesh->status, 200);
    EXPECT_EQ(mesh->body.substr(0, 4), "glTF");
    EXPECT_EQ(mesh->get_header_value("Content-Type"), "model/gltf-binary");
}

TEST_F(StudioServerTest, ExportsPicturesModelsAnimationsAndMusic) {
    // Format, the file's first bytes, its name.
    const std::vector<std::tuple<std::string, std::string, std::string>> exports = {
        {"png", "\x89PNG", "hilbert.png"},        {"pdf", "%PDF", "hilbert.pdf"},
        {"glb", "glTF", "hilbert.glb"},           {"svg", "<", "hilbert.svg"},
        {"ply", "ply\n", "hilbert.ply"},          {"obj", "PK\x03\x04", "hilbert-obj.zip"},
        {"gif", "GIF89a", "hilbert.gif"},         {"mid", "MThd", "hilbert.mid"},
        {"musicxml", "<?xml", "hilbert.musicxml"}};
    for (const auto& [format, start, name] : exports) {
        json body = model(kHilbert);
        body["format"] = format;
        auto res = post("/api/export", body);
        ASSERT_TRUE(res) << format;
        ASSERT_EQ(res->status, 200) << format << ": " << res->body.substr(0, 200);
        EXPECT_EQ(res->body.substr(0, start.size()), start) << format;
        if (format == "png") {  // the picture, not the Hilbert curve's engraved score
            EXPECT_EQ(res->body.substr(16, 8), std::string("\0\0\x03\x20\0\0\x03\x20", 8));
        }
        EXPECT_EQ(res->get_header_value("Content-Disposition"),
                  "attachment; filename=\"" + name + "\"");
    }
    json unknown = model(kHilbert);
    unknown["format"] = "../x";
    EXPECT_EQ(post("/api/export", unknown)->status, 400);
}

TEST_F(StudioServerTest, ObjExportIsAZipOfTheObjAndTheMtlItNames) {
    json body = model(kHilbert);
    body["format"] = "obj";
    const std::string zip = post("/api/export", body)->body;
    // Each stored entry: its local header, the name, the bytes; the directory follows.
    std::map<std::string, std::string> files;
    for (std::size_t at = 0; zip.compare(at, 4, "PK\x03\x04") == 0;) {
        std::uint32_t size = 0;
        std::uint16_t nameLength = 0, extra = 0;
        std::memcpy(&size, zip.data() + at + 18, 4);
        std::memcpy(&nameLength, zip.data() + at + 26, 2);
        std::memcpy(&extra, zip.data() + at + 28, 2);
        const std::string name = zip.substr(at + 30, nameLength);
        files[name] = zip.substr(at + 30 + nameLength + extra, size);
        at += 30 + nameLength + extra + size;
    }
    ASSERT_EQ(files.size(), 2u);
    EXPECT_NE(files["hilbert.obj"].find("mtllib hilbert.mtl\n"), std::string::npos);
    EXPECT_NE(files["hilbert.obj"].find("\nf "), std::string::npos);
    EXPECT_NE(files["hilbert.mtl"].find("newmtl"), std::string::npos);
    // The end record counts both entries.
    const std::size_t end = zip.rfind("PK\x05\x06");
    ASSERT_NE(end, std::string::npos);
    EXPECT_EQ(zip[end + 10], 2);
}

TEST_F(StudioServerTest, ThumbnailIsAPng) {
    auto res = client->Get("/api/thumbnail?path=hilbert.l");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200);
    EXPECT_EQ(res->body.substr(0, 4), "\x89PNG");
    // A view file put beside the model redraws it (45 degree turns: another picture).
    writeText(root / "hilbert.v", "angle increment: 45\n");
    auto withView = client->Get("/api/thumbnail?path=hilbert.l");
    ASSERT_TRUE(withView);
    ASSERT_EQ(withView->status, 200);
    EXPECT_NE(withView->body, res->body);
}

TEST_F(StudioServerTest, WatchAnswersWhenTheFileChanges) {
    auto first = json::parse(client->Get("/api/file?path=hilbert.l")->body);
    const std::int64_t mtime = first["mtime"];
    auto change = std::async(std::launch::async, [&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        writeText(root / "hilbert.l", std::string(kHilbert) + "\n");
        fs::last_write_time(root / "hilbert.l",
                            fs::last_write_time(root / "hilbert.l") + std::chrono::seconds(2));
    });
    httplib::Client watcher("127.0.0.1", port);
    watcher.set_default_headers({{"X-Graftal-Token", server->token()}});
    watcher.set_read_timeout(10, 0);
    auto res = watcher.Get(("/api/watch?path=hilbert.l&since=" + std::to_string(mtime)).c_str());
    change.get();
    ASSERT_TRUE(res);
    json answer = json::parse(res->body);
    EXPECT_TRUE(answer["changed"]);
    EXPECT_NE(answer["mtime"], mtime);
}

TEST_F(StudioServerTest, ANewDerivationCancelsTheSessionsPreviousOne) {
    // A million modules rewritten at every one of 2000 steps: minutes unless stopped.
    const std::string slow =
        "Lsystem: 1\nderivation length: 2000\nAxiom: A(0)\n"
        "A(n) : n < 20 --> A(n+1)A(n+1)\nA(n) : n >= 20 --> A(n+1)\nendlsystem\n";
    auto started = std::chrono::steady_clock::now();
    auto first = std::async(std::launch::async, [&] {
        httplib::Client other("127.0.0.1", port);
        other.set_default_headers({{"X-Graftal-Token", server->token()}});
        other.set_read_timeout(120, 0);
        json body = model(slow);
        auto res = other.Post("/api/derive", body.dump(), "application/json");
        return res ? res->status : -1;
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    auto second = post("/api/derive", model(kHilbert));
    ASSERT_TRUE(second);
    EXPECT_EQ(second->status, 200);
    EXPECT_EQ(first.get(), 409);
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(30));
}

}  // namespace
