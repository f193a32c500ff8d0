#include "sim/devices/modbus_board_server.hpp"

#include <arpa/inet.h>
#include <modbus/modbus.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "control/clock.hpp"

namespace facectl::sim {

namespace {

std::uint16_t crc16(const std::uint8_t* p, std::size_t n) {
  std::uint16_t crc = 0xFFFF;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int b = 0; b < 8; ++b)
      crc = (crc & 1) ? static_cast<std::uint16_t>((crc >> 1) ^ 0xA001)
                      : static_cast<std::uint16_t>(crc >> 1);
  }
  return crc;
}

}  // namespace

ModbusBoardServer::ModbusBoardServer(std::vector<ModbusActuatorBoard*> boards,
                                     modbus_map::Addresses at)
    : boards_(std::move(boards)), at_(at) {
  for (std::size_t i = 0; i < boards_.size(); ++i) {
    maps_.push_back(modbus_mapping_new_start_address(
        0, 0, 0, 0, static_cast<unsigned>(at.control), modbus_map::kHoldingCount,
        static_cast<unsigned>(at.status), modbus_map::kInputCount));
  }
}

std::unique_ptr<ModbusBoardServer> ModbusBoardServer::tcp(std::vector<ModbusActuatorBoard*> boards,
                                                          modbus_map::Addresses at) {
  std::unique_ptr<ModbusBoardServer> s(new ModbusBoardServer(std::move(boards), at));
  s->tcp_ = true;
  s->ctx_ = modbus_new_tcp("127.0.0.1", 0);
  s->listen_fd_ = modbus_tcp_listen(s->ctx_, 1);
  if (s->listen_fd_ < 0) throw std::runtime_error("modbus server: listen failed");
  sockaddr_in addr{};
  socklen_t len = sizeof addr;
  getsockname(s->listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  s->port_ = ntohs(addr.sin_port);
  s->thread_ = std::thread([p = s.get()] { p->run(); });
  return s;
}

std::unique_ptr<ModbusBoardServer> ModbusBoardServer::rtu_pty(ModbusActuatorBoard* board,
                                                              int baud) {
  std::unique_ptr<ModbusBoardServer> s(new ModbusBoardServer({board}, {}));
  s->tcp_ = false;
  int master = -1;
  int slave = -1;
  char name[128] = {};
  if (openpty(&master, &slave, name, nullptr, nullptr) != 0) {
    throw std::runtime_error(std::string("openpty: ") + std::strerror(errno));
  }
  termios tio{};
  tcgetattr(slave, &tio);
  cfmakeraw(&tio);
  tcsetattr(slave, TCSANOW, &tio);
  s->pty_slave_fd_ = slave;
  s->device_ = name;
  s->ctx_ = modbus_new_rtu(name, baud, 'N', 8, 1);
  modbus_set_slave(s->ctx_, board->unit());
  modbus_set_socket(s->ctx_, master);  // serve the master side; the driver opens `name`
  s->client_fd_ = master;
  s->thread_ = std::thread([p = s.get()] { p->run(); });
  return s;
}

ModbusBoardServer::~ModbusBoardServer() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  if (client_fd_ >= 0) close(client_fd_);
  if (listen_fd_ >= 0) close(listen_fd_);
  if (pty_slave_fd_ >= 0) close(pty_slave_fd_);
  modbus_free(ctx_);
  for (auto* m : maps_) modbus_mapping_free(m);
}

void ModbusBoardServer::close_client() {
  if (!tcp_ || client_fd_ < 0) return;
  close(client_fd_);
  client_fd_ = -1;
  modbus_set_socket(ctx_, -1);
}

void ModbusBoardServer::run() {
  while (!stop_.load()) serve_one();
}

void ModbusBoardServer::serve_one() {
  const std::int64_t now = monotonic_ns();
  for (auto* b : boards_) b->advance(now);  // the boards' own loops run without requests
  if (client_fd_ < 0) {
    pollfd p{listen_fd_, POLLIN, 0};
    if (poll(&p, 1, 20) <= 0) return;
    int fd = listen_fd_;
    client_fd_ = modbus_tcp_accept(ctx_, &fd);
    if (client_fd_ >= 0) connections_.fetch_add(1);
    return;
  }
  pollfd p{client_fd_, POLLIN, 0};
  if (poll(&p, 1, 20) <= 0) return;
  std::uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
  const int rc = modbus_receive(ctx_, query);
  if (rc > 0) {
    handle(query, rc);
  } else if (rc < 0 && tcp_) {
    close_client();  // the peer left, or sent garbage: wait for the next one
  } else if (rc < 0) {
    modbus_flush(ctx_);
  }
}

void ModbusBoardServer::handle(const std::uint8_t* query, int length) {
  const int header = modbus_get_header_length(ctx_);
  const int unit = query[header - 1];
  const int function = query[header];
  std::size_t index = 0;
  while (index < boards_.size() && boards_[index]->unit() != unit) ++index;
  const std::uint64_t n = requests_.fetch_add(1) + 1;
  if (index == boards_.size()) {
    modbus_reply_exception(ctx_, query, MODBUS_EXCEPTION_GATEWAY_TARGET);
    return;
  }
  ModbusActuatorBoard& board = *boards_[index];
  modbus_mapping_t* map = maps_[index];

  const int only = faults_.only_unit.load();
  if (only != 0 && only != unit) {
    reply_normally(query, length, board, map, function, header);
    return;
  }
  if (faults_.silent.load()) return;
  const int drop = faults_.drop_every.load();
  if (drop > 0 && n % static_cast<std::uint64_t>(drop) == 0) return;
  if (const int d = faults_.delay_us.load(); d > 0) usleep(static_cast<useconds_t>(d));
  if (faults_.close_connection.exchange(false)) {
    close_client();
    return;
  }
  if (const int code = faults_.exception_code.load(); code != 0) {
    modbus_reply_exception(ctx_, query, static_cast<unsigned>(code));
    return;
  }

  if (faults_.corrupt_next.load() > 0) {
    faults_.corrupt_next.fetch_sub(1);
    send_corrupt(query);
    return;
  }
  reply_normally(query, length, board, map, function, header);
}

void ModbusBoardServer::reply_normally(const std::uint8_t* query, int length,
                                       ModbusActuatorBoard& board, modbus_mapping_t* map,
                                       int function, int header) {
  const std::int64_t now = monotonic_ns();
  board.fill_inputs(now,
                    std::span<std::uint16_t>(map->tab_input_registers,
                                             static_cast<std::size_t>(modbus_map::kInputCount)));
  if (modbus_reply(ctx_, query, length, map) < 0) return;
  if (function == MODBUS_FC_WRITE_MULTIPLE_REGISTERS ||
      function == MODBUS_FC_WRITE_SINGLE_REGISTER) {
    const int addr = ((query[header + 1] << 8) | query[header + 2]) - at_.control;
    const int count = function == MODBUS_FC_WRITE_SINGLE_REGISTER
                          ? 1
                          : ((query[header + 3] << 8) | query[header + 4]);
    const bool targets = addr <= modbus_map::kHrTarget0 && addr + count > modbus_map::kHrTarget0;
    board.apply_holding(
        now,
        std::span<const std::uint16_t>(map->tab_registers,
                                       static_cast<std::size_t>(modbus_map::kHoldingCount)),
        targets);
  }
}

// A well-formed reply of the right length whose integrity check fails: a
// wrong transaction id (TCP) or a wrong CRC (RTU). The client must read all of
// it and reject it, not time out.
void ModbusBoardServer::send_corrupt(const std::uint8_t* query) {
  const int header = modbus_get_header_length(ctx_);
  const int function = query[header];
  std::vector<std::uint8_t> pdu{static_cast<std::uint8_t>(function)};
  if (function == MODBUS_FC_READ_INPUT_REGISTERS) {
    const int count = (query[header + 3] << 8) | query[header + 4];
    pdu.push_back(static_cast<std::uint8_t>(2 * count));
    pdu.resize(pdu.size() + static_cast<std::size_t>(2 * count), 0);
  } else {
    pdu.insert(pdu.end(), query + header + 1, query + header + 5);  // address and count/value echo
  }
  std::vector<std::uint8_t> adu;
  if (tcp_) {
    const auto len = static_cast<std::uint16_t>(pdu.size() + 1);
    adu = {static_cast<std::uint8_t>(query[0] ^ 0xFF),
           static_cast<std::uint8_t>(query[1] ^ 0x5A),
           0,
           0,
           static_cast<std::uint8_t>(len >> 8),
           static_cast<std::uint8_t>(len & 0xFF),
           query[header - 1]};
    adu.insert(adu.end(), pdu.begin(), pdu.end());
  } else {
    adu.push_back(query[0]);
    adu.insert(adu.end(), pdu.begin(), pdu.end());
    const std::uint16_t crc = static_cast<std::uint16_t>(crc16(adu.data(), adu.size()) ^ 0x0101);
    adu.push_back(static_cast<std::uint8_t>(crc & 0xFF));
    adu.push_back(static_cast<std::uint8_t>(crc >> 8));
  }
  [[maybe_unused]] const auto written = ::write(client_fd_, adu.data(), adu.size());
}

}  // namespace facectl::sim
