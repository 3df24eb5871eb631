// `prs view`'s library: what the viewer page shows for a scene (a "view record"), the page
// itself (served, or one self-contained file with the scenes embedded), and a local HTTP
// server that samples scenes on request.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "lang/lang.h"
#include "sampling/sampler.h"

namespace prs::viewer {

/// One scene as the page reads it: {"line": the prs-scene/1 line exactly as `prs sample`
/// writes it, "workspace": {"dimension": d, "vertices": [[x, y, z], ...]} or null (no
/// workspace, or one that is empty or unbounded), "meshes": {PATH: {"vertices": [x, y, z, ...],
/// "triangles": [i, j, k, ...]}, ...}}. Vertices are in metres, world frame; a planar
/// workspace's come in cyclic order. Meshes are keyed by the path the line records for an
/// object's mesh shape, in the mesh's own frame at scale 1 (its bounding box centred).
std::string FormatViewRecord(const sampling::SampledScene& sampled);

/// The record of a scene line read back from a scenes file (`prs sample` output): the line as
/// it is, no workspace (the line does not carry it), and the meshes it names that can be read
/// from their recorded paths.
std::string FormatViewRecordOfLine(std::string_view line);

/// {"error": {"id": ID, "message": MESSAGE}}: what the server answers instead of a record.
std::string FormatErrorRecord(std::string_view id, std::string_view message);

/// What the page starts on.
struct PageInfo {
  std::string title;  // the scenario's file name
  uint64_t seed = 0;
  uint64_t index = 0;
};

/// The page the server sends for "/": it loads "viewer.js" and asks "view?seed=S&index=I".
std::string MakeServedPage(const PageInfo& info);

/// One HTML file with the script inline and `records` (FormatViewRecord texts of scenes
/// info.index, info.index + 1, ...) embedded: it needs no server and no network.
std::string MakeStandalonePage(const PageInfo& info, const std::vector<std::string>& records);

/// An HTTP server on 127.0.0.1 only. Routes: "/" the page, "/viewer.js" the script,
/// "/view?seed=S&index=I" a view record, "/scene?seed=S&index=I" the bare JSON line. A scene
/// that cannot be sampled is answered with FormatErrorRecord (HTTP 422, the message located
/// in the source as on the command line); a bad query with HTTP 400.
class ViewerServer {
 public:
  /// Samples scenes of `program` on request; `program` must outlive the server.
  ViewerServer(const lang::CompiledProgram& program, const sampling::SampleOptions& options,
               PageInfo page);
  /// Serves one fixed page (MakeStandalonePage: scenes read from a file, nothing to sample);
  /// "/view" and "/scene" answer a "not-sampling" error.
  explicit ViewerServer(std::string standalone_page);
  ~ViewerServer();
  ViewerServer(const ViewerServer&) = delete;
  ViewerServer& operator=(const ViewerServer&) = delete;

  /// Binds 127.0.0.1:`port`, or a free port chosen by the system when `port` is 0. Returns
  /// the port. Throws std::runtime_error naming the address when it cannot bind.
  int Bind(int port);
  /// Answers requests until Stop() is called (from another thread). Call after Bind().
  void Listen();
  /// Makes Listen() return; safe to call from any thread, more than once.
  void Stop();

 private:
  void Configure();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace prs::viewer
