#include "hmi/hole_table_model.h"

#include <QCoreApplication>

#include <array>

namespace lcnc::hmi {
namespace {

struct ColumnInfo {
  const char* title;  // operator text, translated (tr)
  const char* unit;
};

// The header: field name and unit (DESIGN §6).
constexpr std::array<ColumnInfo, HoleTableModel::kColumnCount> kColumns = {{
    {QT_TRANSLATE_NOOP("HoleTableModel", "Hole"), ""},
    {QT_TRANSLATE_NOOP("HoleTableModel", "X"), "mm"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Y"), "mm"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Z"), "mm"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "A"), "deg"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "C"), "deg"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Feed"), "mm/min"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Layer feed"), "mm"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Layers"), ""},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Depth"), "mm"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Power"), "%"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Start radius"), "mm"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "End radius"), "mm"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Radius turns"), ""},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Scan speed"), "mm/s"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Wedge speed"), "rpm"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Beam offset"), "mm"},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Process"), ""},
    {QT_TRANSLATE_NOOP("HoleTableModel", "Focus offset"), "mm"},
}};

double* number_of(HoleRecord& r, int column) {
  HoleProcessParams& p = r.params;
  switch (column) {
    case HoleTableModel::kX: return &p.position[0];
    case HoleTableModel::kY: return &p.position[1];
    case HoleTableModel::kZ: return &p.position[2];
    case HoleTableModel::kA: return &p.position[3];
    case HoleTableModel::kC: return &p.position[5];
    case HoleTableModel::kFeed: return &p.feed_mm_min;
    case HoleTableModel::kLayerFeed: return &p.layer_feed_mm;
    case HoleTableModel::kDepth: return &p.total_depth_mm;
    case HoleTableModel::kPower: return &p.power_pct;
    case HoleTableModel::kStartRadius: return &p.head.start_radius_mm;
    case HoleTableModel::kEndRadius: return &p.head.end_radius_mm;
    case HoleTableModel::kScanSpeed: return &p.head.scan_speed_mm_s;
    case HoleTableModel::kWedgeSpeed: return &p.head.wedge_speed_rpm;
    case HoleTableModel::kBeamOffset: return &p.head.beam_offset_mm;
    default: return nullptr;
  }
}

std::uint32_t* count_of(HoleRecord& r, int column) {
  switch (column) {
    case HoleTableModel::kLayers: return &r.params.layer_count;
    case HoleTableModel::kTurns: return &r.params.head.radius_turns;
    default: return nullptr;
  }
}

}  // namespace

HoleTableModel::HoleTableModel(ProcessDatabase& db, QObject* parent) : QAbstractTableModel(parent), db_(db) {
  reload();
}

void HoleTableModel::reload() {
  beginResetModel();
  Result<std::vector<HoleRecord>> all = db_.holes();
  rows_ = all ? std::move(all).value() : std::vector<HoleRecord>{};
  endResetModel();
  if (!all) emit refused(QString::fromStdString(all.error().to_string()));
}

int HoleTableModel::rowCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : static_cast<int>(rows_.size());
}

int HoleTableModel::columnCount(const QModelIndex& parent) const { return parent.isValid() ? 0 : kColumnCount; }

QVariant HoleTableModel::data(const QModelIndex& index, int role) const {
  if (!index.isValid() || index.row() >= rowCount() || index.column() >= kColumnCount) return {};
  if (role != Qt::DisplayRole && role != Qt::EditRole) return {};
  HoleRecord r = rows_[static_cast<std::size_t>(index.row())];
  const int c = index.column();
  if (c == kHole) return r.params.hole_number;
  if (c == kProcess) {
    return role == Qt::EditRole ? QVariant(static_cast<int>(r.params.process))
                                : QVariant(tr(process_name(r.params.process)));
  }
  if (c == kFocus) return r.focus_offset_mm ? QVariant(*r.focus_offset_mm) : QVariant();
  if (std::uint32_t* n = count_of(r, c)) return *n;
  if (double* x = number_of(r, c)) return *x;
  return {};
}

QVariant HoleTableModel::headerData(int section, Qt::Orientation orientation, int role) const {
  if (role != Qt::DisplayRole || orientation != Qt::Horizontal || section < 0 || section >= kColumnCount)
    return QAbstractTableModel::headerData(section, orientation, role);
  const ColumnInfo& c = kColumns[static_cast<std::size_t>(section)];
  // the titles' context is the one QT_TRANSLATE_NOOP names above (tr()'s
  // would be lcnc::hmi::HoleTableModel, where they are not)
  const QString title = QCoreApplication::translate("HoleTableModel", c.title);
  return *c.unit ? title + " (" + QString::fromUtf8(c.unit) + ")" : title;
}

Qt::ItemFlags HoleTableModel::flags(const QModelIndex& index) const {
  Qt::ItemFlags f = QAbstractTableModel::flags(index);
  // the hole number is the row's key; the focus offset is measured, not typed
  if (index.isValid() && index.column() != kHole && index.column() != kFocus) f |= Qt::ItemIsEditable;
  return f;
}

bool HoleTableModel::setData(const QModelIndex& index, const QVariant& value, int role) {
  if (role != Qt::EditRole || !index.isValid() || index.row() >= rowCount()) return false;
  HoleRecord r = rows_[static_cast<std::size_t>(index.row())];
  const int c = index.column();
  bool ok = false;
  if (c == kProcess) {
    const int id = value.toInt(&ok);
    if (!ok || id < 0 || id > 2) {
      emit refused(tr("hole %1: field 18 process = %2; allowed 0 helix, 1 circle, 2 free shape")
                       .arg(r.params.hole_number)
                       .arg(value.toString()));
      return false;
    }
    r.params.process = static_cast<HoleProcessId>(id);
  } else if (std::uint32_t* n = count_of(r, c)) {
    const uint v = value.toUInt(&ok);
    if (!ok) {
      emit refused(tr("hole %1: %2 must be a whole number").arg(r.params.hole_number).arg(headerData(c, Qt::Horizontal).toString()));
      return false;
    }
    *n = v;
  } else if (double* x = number_of(r, c)) {
    const double v = value.toDouble(&ok);
    if (!ok) {
      emit refused(tr("hole %1: %2 must be a number").arg(r.params.hole_number).arg(headerData(c, Qt::Horizontal).toString()));
      return false;
    }
    *x = v;
  } else {
    return false;
  }
  const Status s = db_.put(r);
  if (!s) {
    emit refused(QString::fromStdString(s.error().message));
    return false;
  }
  rows_[static_cast<std::size_t>(index.row())] = r;
  emit dataChanged(index, index, {Qt::DisplayRole, Qt::EditRole});
  return true;
}

}  // namespace lcnc::hmi
