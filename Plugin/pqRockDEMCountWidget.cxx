#include "pqRockDEMCountWidget.h"

#include <pqCoreUtilities.h>
#include <pqLineEdit.h>
#include <vtkCommand.h>
#include <vtkSMIdTypeVectorProperty.h>

#include <QHBoxLayout>
#include <QRegularExpression>
#include <QRegularExpressionValidator>

pqRockDEMCountWidget::pqRockDEMCountWidget(
  vtkSMProxy* proxy, vtkSMProperty* property, QWidget* parent)
  : Superclass(proxy, parent)
  , Edit(new pqLineEdit(this))
{
  this->setProperty(property);
  this->setChangeAvailableAsChangeFinished(false);
  this->Edit->setObjectName("LineEdit0");
  // Whole numbers that fit a 64-bit count; the sign is kept so that a negative count
  // reaches the engine's validation (which names the property and the valid range).
  this->Edit->setValidator(
    new QRegularExpressionValidator(QRegularExpression(R"(-?\d{0,18})"), this->Edit));
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(this->Edit);
  QObject::connect(this->Edit, &pqLineEdit::textEdited, this, &pqRockDEMCountWidget::changeAvailable);
  QObject::connect(this->Edit, &pqLineEdit::textChangedAndEditingFinished, this,
    &pqRockDEMCountWidget::changeFinished);
  // A value set elsewhere (Python, a loaded state, Reset to defaults) is shown.
  pqCoreUtilities::connect(property, vtkCommand::ModifiedEvent, this, SLOT(showValue()));
  this->showValue();
}

pqRockDEMCountWidget::~pqRockDEMCountWidget() = default;

void pqRockDEMCountWidget::apply()
{
  auto* count = vtkSMIdTypeVectorProperty::SafeDownCast(this->property());
  bool ok = false;
  const qlonglong value = this->Edit->text().toLongLong(&ok);
  if (count && ok)
  {
    count->SetElement(0, static_cast<vtkIdType>(value));
  }
  else
  {
    this->showValue(); // nothing typed: the property keeps its value
  }
  this->Superclass::apply();
}

void pqRockDEMCountWidget::reset()
{
  this->showValue();
  this->Superclass::reset();
}

void pqRockDEMCountWidget::showValue()
{
  auto* count = vtkSMIdTypeVectorProperty::SafeDownCast(this->property());
  if (count && count->GetNumberOfElements() > 0)
  {
    this->Edit->setTextAndResetCursor(QString::number(static_cast<qlonglong>(count->GetElement(0))));
  }
}
