#include "hmi/hole_table_model.h"

#include <QCoreApplication>

#include <array>
#include <string_view>

#include "holes/hole_fields.h"

namespace lcnc::hmi {
namespace {

// The header's titles (operator text, translated with tr); the fields'
// units are the field table's (holes/hole_fields.h), the focus offset's mm.
constexpr std::array<const char*, HoleTableModel::kColumnCount> kTitles = {{
    QT_TRANSLATE_NOOP("HoleTableModel", "Hole"),
    QT_TRANSLATE_NOOP("HoleTableModel", "X"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Y"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Z"),
    QT_TRANSLATE_NOOP("HoleTableModel", "A"),
    QT_TRANSLATE_NOOP("HoleTableModel", "C"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Feed"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Layer feed"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Layers"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Depth"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Power"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Start radius"),
    QT_TRANSLATE_NOOP("HoleTableModel", "End radius"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Radius turns"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Scan speed"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Wedge speed"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Beam offset"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Process"),
    QT_TRANSLATE_NOOP("HoleTableModel", "Focus offset"),
}};
constexpr const char* kFocusUnit = "mm";
static_assert(HoleTableModel::kFocus == static_cast<int>(kHoleFields.size()),
              "the columns before the focus offset are the hole record's fields, in order");

}  // namespace

HoleTableModel::HoleTableModel(ProcessDatabase& db, QObject* parent) : QAbstractTableModel(parent), db_(db) {
  reload();
}

void HoleTableModel::reload() {
  beginResetModel();
  Result<std::vector<HoleRecord>> all = db_.holes();
  QString refusal;
  if (all) {
    rows_ = std::move(all).value();
  } else {
    rows_.clear();
    refusal = QString::fromStdString(all.error().to_string());
  }
  endResetModel();
  if (!refusal.isEmpty()) emit refused(refusal);
}

int HoleTableModel::rowCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : static_cast<int>(rows_.size());
}

int HoleTableModel::columnCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : kColumnCount;
}

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
  const HoleField& f = kHoleFields[static_cast<std::size_t>(c)];
  if (f.type == HoleFieldType::Count) return static_cast<uint>(f.get(r.params));
  return f.get(r.params);
}

QVariant HoleTableModel::headerData(int section, Qt::Orientation orientation, int role) const {
  if (role != Qt::DisplayRole || orientation != Qt::Horizontal || section < 0 || section >= kColumnCount)
    return QAbstractTableModel::headerData(section, orientation, role);
  // the titles' context is the one QT_TRANSLATE_NOOP names above (tr()'s
  // would be lcnc::hmi::HoleTableModel, where they are not)
  const QString title =
      QCoreApplication::translate("HoleTableModel", kTitles[static_cast<std::size_t>(section)]);
  const std::string_view unit =
      section == kFocus ? kFocusUnit : kHoleFields[static_cast<std::size_t>(section)].unit;
  return unit.empty() ? title
                      : title + " (" + QString::fromUtf8(unit.data(), static_cast<int>(unit.size())) + ")";
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
  } else if (c == kHole || c == kFocus || c < 0 || c >= kColumnCount) {  // the key; measured
    return false;
  } else if (const HoleField& f = kHoleFields[static_cast<std::size_t>(c)]; f.type == HoleFieldType::Count) {
    const uint v = value.toUInt(&ok);
    if (!ok) {
      emit refused(tr("hole %1: %2 must be a whole number")
                       .arg(r.params.hole_number)
                       .arg(headerData(c, Qt::Horizontal).toString()));
      return false;
    }
    f.set(r.params, v);
  } else {
    const double v = value.toDouble(&ok);
    if (!ok) {
      emit refused(tr("hole %1: %2 must be a number")
                       .arg(r.params.hole_number)
                       .arg(headerData(c, Qt::Horizontal).toString()));
      return false;
    }
    f.set(r.params, v);
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
