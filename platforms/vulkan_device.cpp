// A Vulkan driver as a RasterDevice (platforms/raster_device.h); the measurement itself is
// platforms/readback_measurement.cpp. One submission per draw() (recording, vkQueueSubmit and the
// wait for its fence are what the CPU waits for), an RGBA8 image that stays in
// VK_IMAGE_LAYOUT_GENERAL, a precise occlusion query, and readbacks as copies to a host buffer in a
// second submission, outside the timed one as glReadPixels is outside GL's.
//
// Coordinates. The records must mean what GL's mean: GL window coordinates, y up, pixel (i, j)
// covering [i, i+1] x [j, j+1]. Vulkan's framebuffer y points down and its clip volume is
// 0 <= z <= w (GL: -w <= z <= w). The matrix handed to the shader is the view's projection x
// modelview with row y negated and row z replaced by (z + w) / 2, formed in double: clipping then
// cuts at GL's planes (z' >= 0 is z >= -w, z' <= w is z <= w), and the viewport (0, 0, W, H)
// puts a vertex at framebuffer y = H - y_GL. Framebuffer row r is GL row H - 1 - r, with the same
// pixel centres, and a subpixel grid of 2^-n px in framebuffer y is the same grid in GL's y (H is
// an integer). Only the side of a tie rule flips: a pixel centre exactly on an edge may go to the
// other primitive (Vulkan mandates no tie rule; GL's polygons have none either).
//
// Multisample platforms: drawn into a 4-sample image and resolved with vkCmdResolveImage into a
// single-sample one, which the readback copies.
//
// Layers: the aliased image has layers() array layers and a framebuffer per layer. draw_each()
// records every primitive of the batch in one command buffer: a render pass per run of
// primitives in the same layer, each primitive inside its own occlusion query and, timed, between
// a top-of-pipe and a bottom-of-pipe timestamp; one submission, one fence wait.
//
// The scan on the device (scan(), platforms/vulkan_lit_mask.h): the copies of read() go into a
// device-local buffer, and a compute pass in the same submission leaves a bit per pixel.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "platforms/lit_mask.h"
#include "platforms/raster_device.h"
#include "platforms/vulkan_context.h"
#include "platforms/vulkan_lit_mask.h"
#include "platforms/vulkan_resources.h"

namespace ra::platforms {
namespace {

// A draw() holds at most this many primitives (and the wild point): the vertex buffer's size.
constexpr size_t kMaxPrimitives = 255;
constexpr size_t kMaxVertices = 3 * kMaxPrimitives + 1;

using Clock = std::chrono::steady_clock;
double micros_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

// GL clip coordinates -> Vulkan's (see the top of this file): y negated, z' = (z + w) / 2.
geometry::Mat4 vulkan_clip(const geometry::Mat4& gl_clip_from_object) {
  geometry::Mat4 m = gl_clip_from_object;
  for (int c = 0; c < 4; ++c) {
    m.at(1, c) = -gl_clip_from_object.at(1, c);
    m.at(2, c) = 0.5 * (gl_clip_from_object.at(2, c) + gl_clip_from_object.at(3, c));
  }
  return m;
}

// What one draw of a batch needs: its primitive's first vertex, count, kind and colour.
struct DrawItem {
  uint32_t first = 0, count = 0;
  geometry::Kind kind = geometry::Kind::kPoint;
  uint32_t colour = 0;    // 0xBBGGRR
  bool identity = false;  // vertices already in Vulkan clip coordinates (the test's wild pixel)
};

class VulkanDevice : public RasterDevice {
 public:
  VulkanDevice(const rundir::PlatformSpec& spec, int max_layers)
      : samples_(spec.samples), max_layers_(samples_ > 0 ? 1 : max_layers) {
    ctx_ = std::make_unique<VulkanContext>(spec);
    const VulkanDeviceInfo& d = ctx_->info();
    info_.renderer = d.name;
    info_.version = "Vulkan " + d.api_version + ", " + d.driver;
    info_.vendor =
        d.driver.substr(0, d.driver.find(' ')) + " (vendor id 0x" + hex(d.vendor_id) + ")";
    info_.subpixel_bits = d.subpixel_bits;
    info_.timer_query = d.timestamps;
    info_.max_samples = d.max_samples;
    info_.backend = ctx_->backend();
    info_.line_subpixel_bits = d.line_subpixel_bits;
    info_.strict_lines = d.strict_lines;
    info_.line_modes = d.line_modes();
    info_.line_mode =
        spec.line_mode == rundir::PlatformSpec::LineMode::kBresenham ? "bresenham" : "default";
    pipelines_ = create_pipelines(*ctx_, std::max(samples_, 1), spec.line_mode);
    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = ctx_->queue_family();
    vk_check(vkCreateCommandPool(dev(), &pool, nullptr, &pool_), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    vk_check(vkAllocateCommandBuffers(dev(), &alloc, &cb_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vk_check(vkCreateFence(dev(), &fence, nullptr, &fence_), "vkCreateFence");
    VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    q.queryType = VK_QUERY_TYPE_OCCLUSION;
    q.queryCount = uint32_t(kMaxPrimitives);  // draw() uses the first; draw_each() one each
    vk_check(vkCreateQueryPool(dev(), &q, nullptr, &occlusion_), "vkCreateQueryPool");
    if (d.timestamps) {
      q.queryType = VK_QUERY_TYPE_TIMESTAMP;
      q.queryCount = uint32_t(2 * kMaxPrimitives);
      vk_check(vkCreateQueryPool(dev(), &q, nullptr, &timestamps_), "vkCreateQueryPool");
    }
    vertices_ = create_host_buffer(*ctx_, kMaxVertices * 4 * sizeof(float),
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, false);
  }

  ~VulkanDevice() override {
    vkDeviceWaitIdle(dev());
    lit_mask_.reset();
    destroy_targets();
    destroy_buffer(*ctx_, vertices_);
    destroy_buffer(*ctx_, readback_);
    if (timestamps_) vkDestroyQueryPool(dev(), timestamps_, nullptr);
    vkDestroyQueryPool(dev(), occlusion_, nullptr);
    vkDestroyFence(dev(), fence_, nullptr);
    vkDestroyCommandPool(dev(), pool_, nullptr);
    destroy_pipelines(*ctx_, pipelines_);
  }

  DriverInfo info() const override { return info_; }

  void set_view(const geometry::View& view) override {
    if (view.width != width_ || view.height != height_) resize(view.width, view.height);
    const geometry::Mat4 m = vulkan_clip(view.view_projection);
    for (int i = 0; i < 16; ++i) clip_from_object_[i] = float(m.m[i]);
    if (!warmed_up_) warm_up();
  }
  int width() const override { return width_; }
  int height() const override { return height_; }

  double draw(const std::vector<geometry::Primitive>& prims, const std::vector<uint32_t>& colours,
              bool counted, const geometry::Pixel* wild,
              const std::vector<geometry::PixelRect>* resolve_rects = nullptr) override {
    std::vector<DrawItem> items = load_vertices(prims, colours);
    float* v = static_cast<float*>(vertices_.mapped);
    const uint32_t next = items.empty() ? 0 : items.back().first + items.back().count;
    if (wild) {  // a point at the pixel's centre, in Vulkan clip coordinates
      v[4 * next] = float(2.0 * (wild->x + 0.5) / width_ - 1.0);
      v[4 * next + 1] = float(1.0 - 2.0 * (wild->y + 0.5) / height_);
      v[4 * next + 2] = 0.5f;
      v[4 * next + 3] = 1;
      items.push_back({next, 1, geometry::Kind::kPoint, colours.front(), true});
    }
    each_fragments_.clear();  // counted_fragments() now reads this draw's one query
    each_ticks_.clear();
    const auto t0 = Clock::now();
    record_draws(items, counted);
    if (resolve_rects) record_resolve(*resolve_rects);
    submit_and_wait();
    return micros_since(t0);
  }

  uint64_t counted_fragments() override {
    uint64_t n = 0;
    query_results(occlusion_, 0, 1, &n);
    return n;
  }

  int layers() const override { return int(framebuffers_.size()); }

  double draw_each(const std::vector<geometry::Primitive>& prims,
                   const std::vector<uint32_t>& colours, const std::vector<int>& layers,
                   bool timed) override {
    if (prims.size() > kMaxPrimitives)
      throw std::logic_error("draw_each: more primitives than the vertex buffer holds");
    timed_ = timed && timestamps_;
    std::vector<DrawItem> items = load_vertices(prims, colours);
    const auto t0 = Clock::now();
    begin();
    const uint32_t n = uint32_t(prims.size());
    vkCmdResetQueryPool(cb_, occlusion_, 0, n);
    if (timed_) vkCmdResetQueryPool(cb_, timestamps_, 0, 2 * n);
    const VkQueryControlFlags precise =
        ctx_->info().precise_occlusion ? VK_QUERY_CONTROL_PRECISE_BIT : 0;
    for (uint32_t i = 0; i < n;) {
      uint32_t end = i + 1;  // primitives i..end-1 share a layer: one render pass
      while (end < n && layers[end] == layers[i]) ++end;
      begin_render_pass(framebuffers_[size_t(layers[i])]);
      int bound = -1;
      for (; i < end; ++i) {
        if (timed_) vkCmdWriteTimestamp(cb_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps_, 2 * i);
        vkCmdBeginQuery(cb_, occlusion_, i, precise);
        record_item(items[i], bound);
        vkCmdEndQuery(cb_, occlusion_, i);
        if (timed_)
          vkCmdWriteTimestamp(cb_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps_, 2 * i + 1);
      }
      vkCmdEndRenderPass(cb_);
    }
    submit_and_wait();
    // Every count (and timestamp) of the batch in one call: one call each cost lavapipe 14 us.
    each_fragments_.assign(n, 0);
    query_results(occlusion_, 0, n, each_fragments_.data());
    each_ticks_.assign(timed_ ? 2 * n : 0, 0);
    if (timed_) query_results(timestamps_, 0, 2 * n, each_ticks_.data());
    return micros_since(t0);
  }

  uint64_t fragments_of(size_t i) override {
    if (i < each_fragments_.size()) return each_fragments_[i];
    uint64_t n = 0;
    query_results(occlusion_, uint32_t(i), 1, &n);
    return n;
  }

  double device_us_of(size_t i) override {
    if (!timed_ || 2 * i + 1 >= each_ticks_.size()) return std::numeric_limits<double>::quiet_NaN();
    return timestamp_interval_us(each_ticks_[2 * i], each_ticks_[2 * i + 1],
                                 ctx_->info().timestamp_valid_bits,
                                 ctx_->info().timestamp_period_ns);
  }

  bool device_clock() const override {
    return ctx_->info().timestamps && ctx_->info().type != "cpu";
  }

  void resolve(const std::vector<geometry::PixelRect>& rects) override {
    begin();
    record_resolve(rects);
    submit_and_wait();
  }

  // One copy of every rectangle into the host buffer, one submission.
  void read(const std::vector<geometry::PixelRect>& rects,
            const std::vector<int>& layers) override {
    size_t pixel_count = 0;
    const std::vector<VkBufferImageCopy> copies = image_copies(rects, layers, &pixel_count);
    if (copies.empty()) return;
    if (pixel_count * 4 > readback_.size) {
      destroy_buffer(*ctx_, readback_);
      readback_ = create_host_buffer(*ctx_, std::max<VkDeviceSize>(pixel_count * 4, 1 << 20),
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    }
    begin();
    transfer_barrier();
    vkCmdCopyImageToBuffer(cb_, read_image().image, VK_IMAGE_LAYOUT_GENERAL, readback_.buffer,
                           uint32_t(copies.size()), copies.data());
    VkMemoryBarrier host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cb_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                         &host, 0, nullptr, 0, nullptr);
    submit_and_wait();
  }
  const uint32_t* pixels(size_t i) const override {
    return static_cast<const uint32_t*>(readback_.mapped) + offsets_[i];
  }
  bool rows_top_down() const override { return true; }

  bool scans() const override { return samples_ == 0 && ctx_->info().queue_computes; }

  // The copies of read(), into the scan's device-local buffer, and the pass: one submission.
  void scan(const std::vector<geometry::PixelRect>& rects, const std::vector<int>& layers,
            const std::vector<uint32_t>& colours) override {
    if (!scans()) RasterDevice::scan(rects, layers, colours);
    if (!lit_mask_) lit_mask_ = std::make_unique<VulkanLitMask>(*ctx_);
    scan_layout_ = lay_out_lit_masks(rects, colours);
    if (rects.empty()) return;
    size_t pixel_count = 0;
    const std::vector<VkBufferImageCopy> copies = image_copies(rects, layers, &pixel_count);
    const VkBuffer pixels = lit_mask_->prepare(scan_layout_);
    begin();
    transfer_barrier();
    vkCmdCopyImageToBuffer(cb_, read_image().image, VK_IMAGE_LAYOUT_GENERAL, pixels,
                           uint32_t(copies.size()), copies.data());
    lit_mask_->record(cb_, scan_layout_);
    submit_and_wait();
  }
  const uint32_t* mask(size_t i) const override { return lit_mask_->mask(scan_layout_, i); }
  uint64_t lit_count(size_t i) const override { return lit_mask_->count(i); }

  // Clears both images.
  void clear() override {
    begin();
    transfer_barrier();
    const VkClearColorValue black{{0, 0, 0, 0}};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0,
                                        VK_REMAINING_ARRAY_LAYERS};
    for (VkImage image : {target_.image, resolved_.image})
      if (image) vkCmdClearColorImage(cb_, image, VK_IMAGE_LAYOUT_GENERAL, &black, 1, &range);
    submit_and_wait();
  }

  size_t max_batch() const override { return kMaxPrimitives; }

  // Device timestamps against the CPU clock over the same draws: 8 rounds of 16 window-filling
  // quads at 256 x 256, each one submission; the median of the rounds' ratios (GL uses
  // GL_TIME_ELAPSED). Leaves the window at 256 x 256: set_view() sets it again.
  double timer_over_cpu() override {
    resize(256, 256);
    for (int i = 0; i < 16; ++i) clip_from_object_[i] = i % 5 == 0 ? 1.0f : 0.0f;
    std::vector<geometry::Primitive> quads;
    for (int i = 0; i < 16; ++i)
      for (int half = 0; half < 2; ++half) {
        geometry::Primitive t;
        t.kind = geometry::Kind::kTriangle;
        t.v = half == 0 ? std::array<geometry::Vec3, 3>{geometry::Vec3{-1, -1, 0.5},
                                                        geometry::Vec3{1, -1, 0.5},
                                                        geometry::Vec3{1, 1, 0.5}}
                        : std::array<geometry::Vec3, 3>{geometry::Vec3{-1, -1, 0.5},
                                                        geometry::Vec3{1, 1, 0.5},
                                                        geometry::Vec3{-1, 1, 0.5}};
        quads.push_back(t);
      }
    const std::vector<uint32_t> white(quads.size(), kWhite);
    std::vector<double> ratios;
    for (int round = 0; round < 8; ++round) {
      const double cpu_us = draw(quads, white, true, nullptr);
      uint64_t ticks[2] = {0, 0};
      vk_check(
          vkGetQueryPoolResults(dev(), timestamps_, 0, 2, sizeof ticks, ticks, sizeof(uint64_t),
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
      const double device_us = timestamp_interval_us(
          ticks[0], ticks[1], ctx_->info().timestamp_valid_bits, ctx_->info().timestamp_period_ns);
      if (cpu_us > 0 && std::isfinite(device_us)) ratios.push_back(device_us / cpu_us);
    }
    clear();
    if (ratios.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(ratios.begin(), ratios.end());
    return 0.5 * (ratios[(ratios.size() - 1) / 2] + ratios[ratios.size() / 2]);
  }

 private:
  VkDevice dev() const { return ctx_->device(); }

  // Queries first .. first + count - 1 of `pool` as 64-bit values, waiting for them.
  void query_results(VkQueryPool pool, uint32_t first, uint32_t count, uint64_t* values) {
    vk_check(
        vkGetQueryPoolResults(dev(), pool, first, count, sizeof(uint64_t) * count, values,
                              sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "vkGetQueryPoolResults");
  }
  static std::string hex(uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%04x", v);
    return buf;
  }

  // A copy per rectangle (inside the window) from its layer into a buffer, packed one after
  // another (offsets_); *pixel_count: their pixels in all.
  std::vector<VkBufferImageCopy> image_copies(const std::vector<geometry::PixelRect>& rects,
                                              const std::vector<int>& layers, size_t* pixel_count) {
    offsets_.clear();
    std::vector<VkBufferImageCopy> copies;
    size_t offset = 0;
    for (size_t i = 0; i < rects.size(); ++i) {
      const geometry::PixelRect& r = rects[i];
      offsets_.push_back(offset);
      VkBufferImageCopy c{};
      c.bufferOffset = offset * 4;
      c.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, uint32_t(layers.empty() ? 0 : layers[i]),
                            1};
      c.imageOffset = {r.x0, height_ - r.y1, 0};  // framebuffer y points down
      c.imageExtent = {uint32_t(r.x1 - r.x0), uint32_t(r.y1 - r.y0), 1};
      copies.push_back(c);
      offset += size_t(r.x1 - r.x0) * size_t(r.y1 - r.y0);
    }
    *pixel_count = offset;
    return copies;
  }

  // The image drawn into (4 samples on the multisample platforms) and, there, the resolve target.
  const VulkanImage& read_image() const { return samples_ > 0 ? resolved_ : target_; }

  void resize(int w, int h) {
    destroy_targets();
    const int layers = samples_ > 0 || (max_layers_ == 0 && !device_clock())
                           ? 1
                           : layers_for_window(w, h, max_layers_);
    target_ = create_colour_image(*ctx_, w, h, std::max(samples_, 1), layers);
    if (samples_ > 0) resolved_ = create_colour_image(*ctx_, w, h, 1);
    for (VkImageView view : target_.views) {
      VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
      fb.renderPass = pipelines_.render_pass;
      fb.attachmentCount = 1;
      fb.pAttachments = &view;
      fb.width = uint32_t(w);
      fb.height = uint32_t(h);
      fb.layers = 1;
      framebuffers_.push_back(VK_NULL_HANDLE);
      vk_check(vkCreateFramebuffer(dev(), &fb, nullptr, &framebuffers_.back()),
               "vkCreateFramebuffer");
    }
    width_ = w;
    height_ = h;
    // The images start undefined: into GENERAL, where they stay (vulkan_resources.h).
    begin();
    for (VkImage image : {target_.image, resolved_.image}) {
      if (!image) continue;
      VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
      b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
      b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      b.image = image;
      b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
      vkCmdPipelineBarrier(cb_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           0, 0, nullptr, 0, nullptr, 1, &b);
    }
    submit_and_wait();
  }

  void destroy_targets() {
    for (VkFramebuffer fb : framebuffers_) vkDestroyFramebuffer(dev(), fb, nullptr);
    framebuffers_.clear();
    destroy_image(*ctx_, target_);
    destroy_image(*ctx_, resolved_);
  }

  void begin() {
    vk_check(vkResetCommandBuffer(cb_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo b{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    b.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(cb_, &b), "vkBeginCommandBuffer");
  }

  void submit_and_wait() {
    vk_check(vkEndCommandBuffer(cb_), "vkEndCommandBuffer");
    VkSubmitInfo s{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    s.commandBufferCount = 1;
    s.pCommandBuffers = &cb_;
    vk_check(vkQueueSubmit(ctx_->queue(), 1, &s, fence_), "vkQueueSubmit");
    vk_check(vkWaitForFences(dev(), 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    vk_check(vkResetFences(dev(), 1, &fence_), "vkResetFences");
  }

  // Earlier submissions' transfers and draws before what follows (a copy, a clear, a resolve).
  void transfer_barrier() {
    VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    vkCmdPipelineBarrier(
        cb_, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &b, 0, nullptr, 0, nullptr);
  }

  void record_draws(const std::vector<DrawItem>& items, bool counted) {
    begin();
    if (counted) vkCmdResetQueryPool(cb_, occlusion_, 0, 1);
    if (counted && timestamps_) {
      vkCmdResetQueryPool(cb_, timestamps_, 0, 2);
      vkCmdWriteTimestamp(cb_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps_, 0);
    }
    if (counted)
      vkCmdBeginQuery(cb_, occlusion_, 0,
                      ctx_->info().precise_occlusion ? VK_QUERY_CONTROL_PRECISE_BIT : 0);
    begin_render_pass(framebuffers_.front());
    int bound = -1;
    for (const DrawItem& item : items) record_item(item, bound);
    vkCmdEndRenderPass(cb_);
    if (counted) vkCmdEndQuery(cb_, occlusion_, 0);
    if (counted && timestamps_)
      vkCmdWriteTimestamp(cb_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps_, 1);
  }

  // Writes the primitives' vertices (object coordinates, w = 1) into the vertex buffer.
  std::vector<DrawItem> load_vertices(const std::vector<geometry::Primitive>& prims,
                                      const std::vector<uint32_t>& colours) {
    std::vector<DrawItem> items;
    float* v = static_cast<float*>(vertices_.mapped);
    uint32_t next = 0;
    for (size_t i = 0; i < prims.size(); ++i) {
      const geometry::Primitive& p = prims[i];
      DrawItem item{next, uint32_t(geometry::vertex_count(p.kind)), p.kind, colours[i], false};
      for (uint32_t k = 0; k < item.count; ++k, ++next) {
        v[4 * next] = float(p.v[k].x);
        v[4 * next + 1] = float(p.v[k].y);
        v[4 * next + 2] = float(p.v[k].z);
        v[4 * next + 3] = 1;
      }
      items.push_back(item);
    }
    return items;
  }

  // Begins the render pass on `framebuffer` with the whole window's viewport and scissor and
  // the vertex buffer bound.
  void begin_render_pass(VkFramebuffer framebuffer) {
    VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rp.renderPass = pipelines_.render_pass;
    rp.framebuffer = framebuffer;
    rp.renderArea = {{0, 0}, {uint32_t(width_), uint32_t(height_)}};
    vkCmdBeginRenderPass(cb_, &rp, VK_SUBPASS_CONTENTS_INLINE);
    const VkViewport viewport{0, 0, float(width_), float(height_), 0, 1};
    const VkRect2D scissor{{0, 0}, {uint32_t(width_), uint32_t(height_)}};
    vkCmdSetViewport(cb_, 0, 1, &viewport);
    vkCmdSetScissor(cb_, 0, 1, &scissor);
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cb_, 0, 1, &vertices_.buffer, &offset);
  }

  // One draw inside the render pass: its kind's pipeline (when `bound` is another), its matrix
  // and colour as push constants.
  void record_item(const DrawItem& item, int& bound) {
    if (int(item.kind) != bound) {
      bound = int(item.kind);
      vkCmdBindPipeline(cb_, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_.by_kind[size_t(bound)]);
    }
    DrawConstants c{};
    for (int i = 0; i < 16; ++i)
      c.clip_from_object[i] = item.identity ? (i % 5 == 0 ? 1.0f : 0.0f) : clip_from_object_[i];
    c.colour[0] = float(item.colour & 0xff) / 255.0f;
    c.colour[1] = float((item.colour >> 8) & 0xff) / 255.0f;
    c.colour[2] = float((item.colour >> 16) & 0xff) / 255.0f;
    c.colour[3] = 1;
    vkCmdPushConstants(cb_, pipelines_.layout,
                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof c, &c);
    vkCmdDraw(cb_, item.count, 1, item.first, 0);
  }

  // Records the resolve of the rectangles (same place in both images).
  void record_resolve(const std::vector<geometry::PixelRect>& rects) {
    std::vector<VkImageResolve> resolves;
    for (const geometry::PixelRect& r : rects) {
      VkImageResolve c{};
      c.srcSubresource = c.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      c.srcOffset = c.dstOffset = {r.x0, height_ - r.y1, 0};
      c.extent = {uint32_t(r.x1 - r.x0), uint32_t(r.y1 - r.y0), 1};
      resolves.push_back(c);
    }
    if (resolves.empty()) return;
    transfer_barrier();
    vkCmdResolveImage(cb_, target_.image, VK_IMAGE_LAYOUT_GENERAL, resolved_.image,
                      VK_IMAGE_LAYOUT_GENERAL, uint32_t(resolves.size()), resolves.data());
  }

  // One point, segment and triangle drawn untimed before the first primitive (first-use costs of
  // the driver would otherwise land in the first primitive's render_us); the caller clears.
  void warm_up() {
    geometry::Primitive p, l, t;
    p.kind = geometry::Kind::kPoint;
    l.kind = geometry::Kind::kLine;
    t.kind = geometry::Kind::kTriangle;
    p.v[0] = {0, 0, -0.5};
    l.v[0] = {-0.01, 0, -0.5};
    l.v[1] = {0.01, 0.005, -0.5};
    t.v = {geometry::Vec3{-0.01, -0.01, -0.5}, geometry::Vec3{0.01, -0.01, -0.5},
           geometry::Vec3{0, 0.01, -0.5}};
    const std::vector<geometry::PixelRect> all = {{0, 0, width_, height_}};
    draw({p, l, t}, {1, 1, 1}, true, nullptr, samples_ > 0 ? &all : nullptr);
    read({{0, 0, 1, 1}}, {});
    warmed_up_ = true;
  }

  int samples_ = 0;
  int max_layers_ = 0;  // create_vulkan_device's cap on layers_for_window (0: none)
  std::unique_ptr<VulkanContext> ctx_;
  DriverInfo info_;
  VulkanPipelines pipelines_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cb_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkQueryPool occlusion_ = VK_NULL_HANDLE, timestamps_ = VK_NULL_HANDLE;
  VulkanBuffer vertices_, readback_;
  VulkanImage target_, resolved_;
  std::vector<VkFramebuffer> framebuffers_;  // one per layer of target_
  bool timed_ = false;                       // the last draw_each wrote timestamps
  std::vector<uint64_t> each_fragments_;     // the last draw_each's counts, per primitive
  std::vector<uint64_t> each_ticks_;         // and its timestamps, two per primitive (timed)
  int width_ = 0, height_ = 0;
  float clip_from_object_[16] = {};
  bool warmed_up_ = false;
  std::vector<size_t> offsets_;  // where each rectangle of the last read() starts in readback_
  std::unique_ptr<VulkanLitMask> lit_mask_;  // the scan on the device, made at its first use
  LitMaskLayout scan_layout_;                // of the last scan()
};

}  // namespace

std::unique_ptr<RasterDevice> create_vulkan_device(const rundir::PlatformSpec& spec,
                                                   int max_layers) {
  return std::make_unique<VulkanDevice>(spec, max_layers);
}

}  // namespace ra::platforms
