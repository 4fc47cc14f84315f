#include "drivers/sick/start_sequence.h"

#include "drivers/sick/commands.h"
#include "drivers/sick/scan_telegram_codec.h"

namespace fleetmap::drivers::sick {
namespace {

// What a request's reply is called: "sMN X" is answered by "sAN X", "sEN X" by "sEA X".
struct ExpectedReply {
  std::string type, name;
  bool may_be_refused = false;  // LMCstartmeas and Run
};

ExpectedReply ReplyTo(const std::string& request) {
  const ColaCommand c = SplitCommand(request).value();  // our own requests always split
  ExpectedReply e;
  e.type = c.type == "sEN" ? "sEA" : c.type == "sRN" ? "sRA" : "sAN";
  e.name = std::string(c.name);
  e.may_be_refused = e.name == "LMCstartmeas" || e.name == "Run";
  return e;
}

// The refusal carried by a reply, or empty when the device accepted.
std::string Refusal(const ParsedCommand& reply) {
  if (!reply.has_value) return "";
  if (reply.name == "SetAccessMode" && reply.value == 0) return "refused the login";
  if (reply.name == "Run" && reply.value == 0) return "refused Run";
  if (reply.name == "LMCstartmeas" && reply.value != 0) {
    return "refused LMCstartmeas (code " + std::to_string(reply.value) + ")";
  }
  if (reply.name == "LMDscandata" && reply.type == "sEA" && reply.value == 0) {
    return "refused to stream LMDscandata";
  }
  return "";
}

// Reads until the reply to `request` (or sFA) arrives; returns its refusal text, if any.
core::Result<std::string> AwaitReply(TcpConnection& connection, TelegramSplitter& splitter,
                                     const ExpectedReply& expected,
                                     const StartSequenceOptions& options,
                                     StartSequenceResult& result) {
  const double deadline = MonotonicNowS() + options.reply_timeout_s;
  uint8_t buffer[4096];
  while (true) {
    while (std::optional<std::string> payload = splitter.Next()) {
      if (IsScanTelegram(*payload)) {
        ++result.other_telegrams;
        continue;
      }
      core::Result<ParsedCommand> reply = ParseCommand(*payload, options.protocol);
      if (!reply.ok()) {
        ++result.other_telegrams;
        continue;
      }
      if (reply->type == "sFA") {
        ++result.error_replies;
        return "answered sFA " + std::to_string(reply->value) + " to " + expected.name;
      }
      if (reply->type == expected.type && reply->name == expected.name) {
        result.login_refused |= reply->name == "SetAccessMode" && reply->value == 0;
        return Refusal(*reply);
      }
      ++result.other_telegrams;  // an event or a late reply
    }
    const double left = deadline - MonotonicNowS();
    if (left <= 0.0) {
      return core::IoError("no reply to \"" + expected.name + "\" within " +
                           std::to_string(options.reply_timeout_s) + " s");
    }
    core::Result<size_t> n = connection.Read(buffer, sizeof(buffer), left);
    if (!n.ok()) return n.status();
    splitter.Feed(buffer, *n);
  }
}

}  // namespace

std::vector<std::string> StartRequests(const StartSequenceOptions& options) {
  std::vector<std::string> requests;
  if (options.login) requests.push_back(SetAccessModeRequest(options.protocol));
  if (options.start_measurement) {
    requests.push_back(StartMeasurementRequest());
    requests.push_back(RunRequest());
  }
  if (options.streaming) requests.push_back(ScanStreamRequest(options.protocol, true));
  return requests;
}

StartSequenceResult RunStartSequence(TcpConnection& connection, TelegramSplitter& splitter,
                                     const StartSequenceOptions& options) {
  StartSequenceResult result;
  for (const std::string& request : StartRequests(options)) {
    result.status =
        connection.WriteAll(FrameTelegram(options.protocol, request), options.reply_timeout_s);
    if (!result.status.ok()) return result;
    const ExpectedReply expected = ReplyTo(request);
    core::Result<std::string> refusal = AwaitReply(connection, splitter, expected, options, result);
    if (!refusal.ok()) {
      result.status = refusal.status();
      return result;
    }
    if (refusal->empty()) continue;
    if (!expected.may_be_refused) {
      result.status = core::FailedPrecondition("scanner " + *refusal);
      return result;
    }
    result.refused.push_back(*refusal);
  }
  return result;
}

}  // namespace fleetmap::drivers::sick
