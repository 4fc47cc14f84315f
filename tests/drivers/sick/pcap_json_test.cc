// Wireshark's JSON export read as a recording: a packet's time is outside data like the rest.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "sim/sick/recording_reader.h"

namespace fleetmap::drivers::sick {
namespace {

namespace fs = std::filesystem;

// One exported packet whose tcp layer carries `time_relative` (a JSON value) and 4 bytes.
std::string WritePacket(const std::string& time_relative) {
  const fs::path path =
      fs::temp_directory_path() / ("fleetmap_pcap_json_" + std::to_string(getpid()) + ".json");
  std::ofstream(path) << R"([{"_source": {"layers": {"tcp": {"tcp.payload": "02:02:02:02",)"
                      << R"("Timestamps": {"tcp.time_relative": )" << time_relative << "}}}}}]";
  return path.string();
}

TEST(PcapJsonTest, APacketTimeThatIsNoNumberIsAnErrorNamingTheField) {
  for (const std::string bad : {R"("0.5s")", R"("")", "0.5"}) {
    const std::string path = WritePacket(bad);
    const core::Result<sim::sick::Recording> r = sim::sick::ReadPcapJson(path);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_NE(r.status().ToString().find("tcp.time_relative"), std::string::npos)
        << r.status().ToString();
    fs::remove(path);
  }
}

TEST(PcapJsonTest, APacketWithAReadableTimeIsRead) {
  const std::string path = WritePacket(R"("0.125")");
  const core::Result<sim::sick::Recording> r = sim::sick::ReadPcapJson(path);
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  fs::remove(path);
}

}  // namespace
}  // namespace fleetmap::drivers::sick
