// graftal studio's server as the page's connection sees it: answers on a kept-alive
// connection come at once, without the 40 ms a delayed ACK adds to an answer whose headers
// and body are written apart while Nagle's algorithm holds the body back.
#include <gtest/gtest.h>
#include <httplib.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "graftal/studio/studio_server.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

class StudioConnectionTest : public ::testing::Test {
  protected:
    void SetUp() override {
        root = fs::temp_directory_path() /
               ("graftal-studio-connection-" + std::to_string(::getpid()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(root);
        fs::create_directories(root);
        std::ofstream(root / "koch.l") << "Lsystem: 1\nderivation length: 3\nangle factor: 4\n"
                                          "axiom: F\nF --> F+F-F-F+F\nendlsystem\n";
        graftal::studio::StudioOptions options;
        options.root = root;
        options.requireToken = false;  // raw requests: the token is tested elsewhere
        server = std::make_unique<graftal::studio::StudioServer>(options);
        port = server->start(0);
    }
    void TearDown() override {
        server.reset();
        fs::remove_all(root);
    }

    // Milliseconds of each of `count` small answers asked one after another on one
    // connection, as the page asks them (its client does not hold its own writes back).
    std::vector<double> answerTimes(const std::string& path, const json& body, int count) {
        httplib::Client client("127.0.0.1", port);
        client.set_keep_alive(true);
        client.set_tcp_nodelay(true);
        client.set_read_timeout(30, 0);
        std::vector<double> times;
        for (int i = 0; i < count; ++i) {
            const auto start = std::chrono::steady_clock::now();
            auto res = body.is_null() ? client.Get(path.c_str())
                                      : client.Post(path.c_str(), body.dump(), "application/json");
            times.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count());
            if (!res) {
                ADD_FAILURE() << path << " was not answered";
                continue;
            }
            EXPECT_EQ(res->status, 200) << res->body;
        }
        return times;
    }

    static double median(std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    }

    fs::path root;
    std::unique_ptr<graftal::studio::StudioServer> server;
    int port = 0;
};

// Each answer of a kept-alive connection waited for the browser's delayed ACK (40 ms on
// Linux) before the server turned Nagle's algorithm off: a parse answer took 45 ms.
TEST_F(StudioConnectionTest, SmallAnswersOnAKeptConnectionComeWithoutWaitingForAnAck) {
    const json body = {{"text", "Lsystem: 1\naxiom: F\nendlsystem\n"}, {"path", "koch.l"}};
    const std::vector<double> parse = answerTimes("/api/parse", body, 15);
    EXPECT_LT(median(parse), 25.0) << "a delayed ACK is at least 40 ms";
    const std::vector<double> info = answerTimes("/api/info", json(), 15);
    EXPECT_LT(median(info), 25.0);
}

}  // namespace
