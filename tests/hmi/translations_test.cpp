// The HMI's languages: every operator text of the sources (as Qt Linguist's
// lupdate finds it in the .cpp and .ui files today) has a Chinese and a
// Russian translation, and the screens speak them once installed.
#include <gtest/gtest.h>

#include <unistd.h>

#include <QAbstractButton>
#include <QAbstractItemView>
#include <QAbstractSpinBox>
#include <QComboBox>
#include <QFile>
#include <QGroupBox>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QRegularExpression>
#include <QTabWidget>
#include <QTableView>
#include <QTableWidget>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "hmi/main_window.h"
#include "hmi/process_db.h"
#include "hmi/translations.h"

namespace lcnc::hmi {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Translations, EveryOperatorTextHasAChineseAndARussianTranslation) {
  const fs::path dir = fs::temp_directory_path() / ("lcnc_ts_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path src = LCNC_SOURCE_DIR;
  for (const char* lang : {"zh_CN", "ru"}) {
    const std::string name = std::string("lasercnc_hmi_") + lang + ".ts";
    const fs::path committed = src / "hmi" / "translations" / name, fresh = dir / name;
    fs::copy_file(committed, fresh);
    // lupdate over today's sources into a copy of the committed file: a text
    // added or changed since shows as new (and unfinished)
    const std::string cmd = "cd " + src.string() + " && " + LUPDATE_EXE +
                            " -I . -no-obsolete -locations none hmi/*.cpp hmi/*.h hmi/*.ui -ts " +
                            fresh.string() + " > " + (dir / "lupdate.txt").string() + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir / "lupdate.txt");
    const std::string out = slurp(dir / "lupdate.txt");
    EXPECT_NE(out.find("(0 new and"), std::string::npos) << lang << ": texts not in the translation file\n"
                                                         << out;
    const std::string ts = slurp(fresh);
    EXPECT_EQ(ts.find("type=\"unfinished\""), std::string::npos) << lang << ": untranslated texts";
    EXPECT_EQ(ts.find("<translation></translation>"), std::string::npos) << lang;
    EXPECT_GT(std::count(ts.begin(), ts.end(), '\n'), 500) << lang;  // the whole HMI, not a stub
  }
  fs::remove_all(dir);
}

TEST(Translations, TheScreensSpeakRussianAndChinese) {
  auto db = ProcessDatabase::open(
      (fs::temp_directory_path() / ("lcnc_tr_" + std::to_string(getpid()) + ".db")).string());
  ASSERT_TRUE(static_cast<bool>(db));
  const auto tab_titles = [&] {
    MainWindow w(**db, "/lcnc_tr_none");
    QStringList titles;
    for (int i = 0; i < w.screens()->count(); ++i) titles << w.screens()->tabText(i);
    titles << w.findChild<QPushButton*>("estopButton")->text();
    return titles;
  };
  ASSERT_TRUE(install_language("ru"));
  QStringList ru = tab_titles();
  EXPECT_EQ(ru[0], QString::fromUtf8("Станок"));
  EXPECT_TRUE(ru.contains(QString::fromUtf8("Фокусное расстояние"))) << ru.join("|").toStdString();
  EXPECT_EQ(ru.last(), QString::fromUtf8("АВАР. СТОП"));
  ASSERT_TRUE(install_language("zh_CN"));
  QStringList zh = tab_titles();
  EXPECT_EQ(zh[0], QString::fromUtf8("机床"));
  EXPECT_EQ(zh.last(), QString::fromUtf8("急停"));
  ASSERT_TRUE(install_language("en"));
  EXPECT_EQ(tab_titles()[0], "Machine");
  QString why;
  EXPECT_FALSE(install_language("de", &why));
  EXPECT_TRUE(why.contains("no translation for 'de'")) << why.toStdString();
}

// Every text a screen shows: each widget's by its object path, with what
// kind of text it is (a label, a button, a tab, a column title, a combo
// item, a placeholder, a tooltip).
std::map<std::string, QString> visible_texts(QWidget& root) {
  std::map<std::string, QString> out;
  const auto path_of = [&root](const QObject* o) {
    std::string p;
    for (; o != nullptr && o != &root; o = o->parent())
      p = (o->objectName().isEmpty() ? std::string(o->metaObject()->className())
                                     : o->objectName().toStdString()) +
          "/" + p;
    return p;
  };
  const auto put = [&out](const std::string& key, const QString& text) {
    if (!text.trimmed().isEmpty()) out[key] = text;
  };
  for (QWidget* w : root.findChildren<QWidget*>()) {
    const std::string p = path_of(w);
    if (auto* l = qobject_cast<QLabel*>(w)) put(p + "text", l->text());
    if (auto* b = qobject_cast<QAbstractButton*>(w)) put(p + "text", b->text());
    if (auto* g = qobject_cast<QGroupBox*>(w)) put(p + "title", g->title());
    if (auto* e = qobject_cast<QLineEdit*>(w)) put(p + "placeholder", e->placeholderText());
    if (auto* s = qobject_cast<QAbstractSpinBox*>(w)) put(p + "special", s->specialValueText());
    if (auto* c = qobject_cast<QComboBox*>(w))
      for (int i = 0; i < c->count(); ++i) put(p + "item" + std::to_string(i), c->itemText(i));
    if (auto* t = qobject_cast<QTabWidget*>(w))
      for (int i = 0; i < t->count(); ++i) put(p + "tab" + std::to_string(i), t->tabText(i));
    if (auto* v = qobject_cast<QAbstractItemView*>(w); v && v->model())
      for (int c = 0; c < v->model()->columnCount(); ++c)
        put(p + "column" + std::to_string(c), v->model()->headerData(c, Qt::Horizontal).toString());
    put(p + "tooltip", w->toolTip());
  }
  return out;
}

// A text that may read the same in every language: symbols, numbers, axis
// letters, G-code, units, names.
bool language_neutral(const QString& text) {
  static const QRegularExpression word("[A-Za-z]{2,}");
  static const QRegularExpression unit("\\b(mm|cm|m|deg|rpm|W|s)\\b");
  static const QStringList names = {"LaserCNC", "MDI", "DXF (*.dxf)", "CSV (*.csv)", "a_eff mm/s²"};
  QString rest = text;
  rest.remove(unit);
  return !word.match(rest).hasMatch() || names.contains(text);
}

// Each screen rendered in Russian and in Chinese: no visible text stays as
// it reads in English (a text never marked, marked in another context, or
// not translated), and the window fits a 1280 × 800 panel in every language.
TEST(Translations, NoScreenShowsAnUntranslatedText) {
  auto db = ProcessDatabase::open(
      (fs::temp_directory_path() / ("lcnc_tr3_" + std::to_string(getpid()) + ".db")).string());
  ASSERT_TRUE(static_cast<bool>(db));
  const auto render = [&](const char* language) {
    EXPECT_TRUE(install_language(language));
    MainWindow w(**db, "/lcnc_tr_none");
    w.screenshot_all(QString::fromStdString(
        (fs::temp_directory_path() / ("lcnc_tr3_" + std::to_string(getpid()))).string()));
    EXPECT_LE(w.minimumSizeHint().width(), 1280) << language;
    EXPECT_LE(w.minimumSizeHint().height(), 800) << language;
    for (int i = 0; i < w.screens()->count(); ++i) {
      const QSize hint = w.screens()->widget(i)->minimumSizeHint();
      EXPECT_LE(hint.width(), 1270) << language << " " << w.screens()->widget(i)->objectName().toStdString();
      EXPECT_LE(hint.height(), 760) << language << " " << w.screens()->widget(i)->objectName().toStdString();
    }
    return visible_texts(w);
  };
  const std::map<std::string, QString> en = render("en");
  EXPECT_GT(en.size(), 150u);
  for (const char* language : {"ru", "zh_CN"}) {
    const std::map<std::string, QString> shown = render(language);
    for (const auto& [where, text] : en) {
      const auto it = shown.find(where);
      if (it == shown.end() || language_neutral(text)) continue;
      EXPECT_NE(it->second, text) << language << ": untranslated '" << text.toStdString() << "' at " << where;
    }
  }
  ASSERT_TRUE(install_language("en"));
}

// Texts the code translates from tables of its own (column titles, the
// probe faces): in the context they were marked in, not tr()'s namespaced
// one — the hole table's and the decomposition's headers stayed English in
// Russian and Chinese before.
TEST(Translations, TableHeadersFromTheCodesOwnListsAreTranslated) {
  auto db = ProcessDatabase::open(
      (fs::temp_directory_path() / ("lcnc_trh_" + std::to_string(getpid()) + ".db")).string());
  ASSERT_TRUE(static_cast<bool>(db));
  ASSERT_TRUE(install_language("ru"));
  {
    MainWindow w(**db, "/lcnc_tr_none");
    QAbstractItemModel* holes = nullptr;
    for (QTableView* v : w.findChildren<QTableView*>())
      if (v->model() != nullptr && QString(v->model()->metaObject()->className()).endsWith("HoleTableModel"))
        holes = v->model();
    ASSERT_NE(holes, nullptr);
    EXPECT_TRUE(holes->headerData(0, Qt::Horizontal).toString().startsWith(QString::fromUtf8("Отверстие")))
        << holes->headerData(0, Qt::Horizontal).toString().toStdString();
    auto* contours = w.findChild<QTableWidget*>("contourTable");
    ASSERT_NE(contours, nullptr);
    EXPECT_EQ(contours->horizontalHeaderItem(1)->text(), QString::fromUtf8("первый элемент"));
  }
  ASSERT_TRUE(install_language("zh_CN"));
  {
    MainWindow w(**db, "/lcnc_tr_none");
    EXPECT_EQ(w.findChild<QTableWidget*>("contourTable")->horizontalHeaderItem(2)->text(),
              QString::fromUtf8("长度 mm"));
  }
  ASSERT_TRUE(install_language("en"));
}

}  // namespace
}  // namespace lcnc::hmi
